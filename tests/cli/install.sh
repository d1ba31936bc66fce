#!/bin/sh
# The installed library as a user sees it: `make install` into a temporary prefix (the tree, the
# SONAME and version, only whirl_* symbols exported from libwhirl.so and every function the
# headers declare among them, whirl.h including every header, each header compiling on its own,
# whirl.pc, the manual page holding every option of every `whirl CMD --help`); every example of
# examples/ compiled outside the repository with `pkg-config --cflags --libs whirl` only, run
# against the shared library and its output compared with examples/NAME.out (numbers to the
# last printed digit); one example linked
# statically; DESTDIR staging, `make uninstall`, and an unwritable prefix failing cleanly.
# Run by `make check` (plain build) as: tests/run.sh BUILD --also tests/cli/install.sh.
. "$(dirname "$0")/lib.sh"
build=$(dirname "$WHIRL")
repo=$(pwd)
prefix=$tmp/prefix
mk() { make -s --no-print-directory -C "$repo" BUILD="$build" "$@"; }

# ---- install into a prefix ----
before=$(stat -c '%Y.%i' "$build/whirl" "$build/whirl.1" "$build/gen/datadir.h" | tr '\n' ' ')
if mk install PREFIX="$prefix" >"$tmp/install.out" 2>&1; then pass "make install PREFIX=..."
else fail "make install PREFIX=...: $(tail -n 3 "$tmp/install.out")"; finish; fi
# the build tree as it was: its program not relinked, and up to date for the next make
after=$(stat -c '%Y.%i' "$build/whirl" "$build/whirl.1" "$build/gen/datadir.h" | tr '\n' ' ')
if [ "$before" = "$after" ] && mk -q "$build/whirl" "$build/whirl.1" \
   && ! "$WHIRL" simulate --help | grep -q "$prefix"; then
  pass "make install PREFIX=...: the build tree's program untouched, still up to date"
else fail "make install PREFIX=... changed the build tree ($before -> $after)"; fi
if "$prefix/bin/whirl" simulate --help | grep -q "examples in $prefix/share/whirl/scenes" \
   && grep -q "$prefix/share/whirl" "$prefix/share/man/man1/whirl.1"; then
  pass "the installed program and manual page name $prefix/share/whirl"
else fail "the installed program does not name its data: $("$prefix/bin/whirl" simulate --help | head -2)"; fi
version=$(awk '$2 == "WHIRL_VERSION_MAJOR" { a = $3 } $2 == "WHIRL_VERSION_MINOR" { b = $3 }
               $2 == "WHIRL_VERSION_PATCH" { c = $3 } END { print a "." b "." c }' include/whirl/version.h)
major=${version%%.*}
missing=""
for f in bin/whirl lib/libwhirl.a lib/libwhirl.so.$version lib/libwhirl.so.$major lib/libwhirl.so \
         lib/pkgconfig/whirl.pc include/whirl.h share/man/man1/whirl.1 \
         share/whirl/scenes/classroom.ini share/whirl/scenes/mode2.ini share/whirl/plots/animate.gp \
         share/whirl/fit_example.csv \
         $(cd include && ls whirl/*.h); do
  case $f in whirl/*) f=include/$f ;; esac
  [ -e "$prefix/$f" ] || missing="$missing $f"
done
if [ -z "$missing" ]; then pass "installed tree complete ($(find "$prefix" -type f -o -type l | wc -l) files)"
else fail "installed tree lacks:$missing"; fi
if [ "$(readlink "$prefix/lib/libwhirl.so")" = "libwhirl.so.$major" ] \
   && [ "$(readlink "$prefix/lib/libwhirl.so.$major")" = "libwhirl.so.$version" ] \
   && objdump -p "$prefix/lib/libwhirl.so.$version" | grep -q "SONAME  *libwhirl.so.$major\$"; then
  pass "SONAME libwhirl.so.$major, links to libwhirl.so.$version"
else fail "SONAME / links: $(objdump -p "$prefix/lib/libwhirl.so.$version" | grep SONAME)"; fi

# ---- exported symbols ----
nm -D --defined-only "$prefix/lib/libwhirl.so" | awk '{ print $NF }' | sort >"$tmp/exported"
other=$(grep -v '^whirl_' "$tmp/exported" | tr '\n' ' ')
if [ -s "$tmp/exported" ] && [ -z "$other" ]; then
  pass "nm -D: all $(wc -l <"$tmp/exported") exported symbols start with whirl_"
else fail "nm -D: exported symbols not whirl_*: $other"; fi
# every function and object declared WHIRL_API in the installed headers is exported, and
# nothing else
sed -n -e 's/^WHIRL_API[^(]*[ *]\(whirl_[a-z0-9_]*\)(.*/\1/p' \
  -e 's/^extern WHIRL_API .*[ *]\(whirl_[a-z0-9_]*\);.*/\1/p' "$prefix"/include/whirl/*.h |
  sort -u >"$tmp/declared"
if [ "$(wc -l <"$tmp/declared")" -ge 80 ] && cmp -s "$tmp/declared" "$tmp/exported"; then
  pass "nm -D: exactly the $(wc -l <"$tmp/declared") functions declared WHIRL_API"
else fail "declared vs exported: $(diff "$tmp/declared" "$tmp/exported" | grep '^[<>]' | head -5 | tr '\n' ' ')"; fi
# no function declaration in a header without WHIRL_API
bare=$(grep -hE '^[a-z][a-z_ ]*[ *]whirl_[a-z0-9_]*\(' "$prefix"/include/whirl/*.h | head -3)
if [ -z "$bare" ]; then pass "every function declaration carries WHIRL_API"
else fail "declarations without WHIRL_API: $bare"; fi
for s in whirl_version whirl_last_error whirl_nlink_solve whirl_continuum_solve \
         whirl_stability_mode whirl_integrator_alloc whirl_regime_run; do
  grep -qx "$s" "$tmp/exported" || { fail "nm -D: $s not exported"; s=""; break; }
done
[ -n "$s" ] && pass "nm -D: the key functions exported"

# ---- headers, pkg-config ----
export PKG_CONFIG_PATH="$prefix/lib/pkgconfig"
mkdir -p "$tmp/user" && cd "$tmp/user" || exit 1
cflags=$(pkg-config --cflags whirl) && libs=$(pkg-config --libs whirl)
if [ "$(pkg-config --modversion whirl)" = "$version" ] && echo "$libs" | grep -q -- "-L$prefix/lib" \
   && echo "$cflags" | grep -q -- "-I$prefix/include"; then
  pass "pkg-config: whirl $version, -I and -L in the prefix"
else fail "pkg-config: $(pkg-config --modversion whirl) / $cflags / $libs"; fi
notin=""
for h in $(cd "$prefix/include" && ls whirl/*.h); do
  grep -q "^#include \"$h\"" "$prefix/include/whirl.h" || notin="$notin $h"
done
if [ -z "$notin" ]; then pass "whirl.h includes every header"; else fail "whirl.h lacks:$notin"; fi
bad=""
for h in $(cd "$prefix/include" && ls whirl.h whirl/*.h); do
  printf '#include <%s>\n#include <%s>\n' "$h" "$h" >alone.c
  cc -std=c11 -Wall -Wextra -Wpedantic -Werror $cflags -c alone.c -o alone.o 2>>alone.err || bad="$bad $h"
done
if [ -z "$bad" ]; then pass "each header compiles on its own, twice included, -Wpedantic -Werror"
else fail "headers not standalone:$bad: $(head -c 300 alone.err)"; fi
cat >version.c <<'EOF'
#include <stdio.h>
#include <string.h>
#include <whirl.h>
int main(void)
{
    printf("%s %d.%d.%d\n", whirl_version(), WHIRL_VERSION_MAJOR, WHIRL_VERSION_MINOR,
           WHIRL_VERSION_PATCH);
    return strcmp(whirl_version(), WHIRL_VERSION) != 0;
}
EOF
if cc version.c $cflags $libs -o version 2>cc.err \
   && [ "$(LD_LIBRARY_PATH="$prefix/lib" ./version)" = "$version $version" ] \
   && [ "$("$prefix/bin/whirl" --version)" = "whirl $version (library $version)" ]; then
  pass "whirl_version(), WHIRL_VERSION and whirl --version agree: $version"
else fail "version: $(LD_LIBRARY_PATH="$prefix/lib" ./version) / $("$prefix/bin/whirl" --version) $(head -c 200 cc.err)"; fi

# ---- the manual page holds every option of every command's --help ----
sed 's/\\-/-/g; s/\\f[BIRP]//g' "$prefix/share/man/man1/whirl.1" >man.txt
absent=""
for cmd in $("$prefix/bin/whirl" --help | sed -n '/^commands:/,$p' | awk 'NR > 1 { print $1 }'); do
  grep -q "^\.SS whirl $cmd\$" man.txt || absent="$absent $cmd"
  for opt in $("$prefix/bin/whirl" "$cmd" --help | grep -oE '(^|[][ ,|])--?[A-Za-z][A-Za-z0-9-]*' \
               | sed 's/^[][ ,|]//' | sort -u); do
    grep -qE -- "(^|[][ ,|])$opt([][ ,|]|\$)" man.txt || absent="$absent $cmd:$opt"
  done
done
grep -qE -- '(^| )--version( |$)' man.txt || absent="$absent --version"
ncmd=$("$prefix/bin/whirl" --help | sed -n '/^commands:/,$p' | awk 'NR > 1' | wc -l)
if [ -z "$absent" ] && [ "$ncmd" -ge 9 ]; then pass "whirl(1) holds every option of the $ncmd commands' --help"
else fail "whirl(1) lacks:$absent"; fi

# ---- the examples, built against the installed library with pkg-config only ----
# an example's output against the stored one: the same words, and each number within 2 units of
# the last digit printed in the stored output (a rounding that tips over, not a change)
same_output() {
  awk 'function num(x) { return x ~ /^[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?$/ }
       function abs(x) { return x < 0 ? -x : x }
       function unit(x,   m, e, d) {
         e = 0; m = x
         if (match(x, /[eE]/)) { e = substr(x, RSTART + 1) + 0; m = substr(x, 1, RSTART - 1) }
         d = index(m, ".") ? length(m) - index(m, ".") : 0
         return 10 ^ (e - d) }
       NR == FNR { want[FNR] = $0; nw = FNR; next }
       { ng = FNR; if (FNR > nw) { bad = 1; exit }
         n = split(want[FNR], a, /[ \t=,:;()]+/); m = split($0, b, /[ \t=,:;()]+/)
         if (n != m) { bad = 1; exit }
         for (i = 1; i <= n; i++)
           if (num(a[i]) && num(b[i])) {
             if (abs(a[i] - b[i]) > 2 * unit(a[i])) { bad = 1; exit }
           } else if (a[i] != b[i]) { bad = 1; exit } }
       END { exit bad || ng != nw }' "$1" "$2"
}
nex=0
for src in "$repo"/examples/*.c; do
  [ -f "$src" ] || continue
  name=$(basename "$src" .c)
  nex=$((nex + 1))
  cp "$src" "$tmp/user/$name.c"
  if ! cc -std=c11 -Wall -Wextra -Werror -o "$name" "$name.c" $(pkg-config --cflags --libs whirl) 2>"$name.err"; then
    fail "example $name: compile: $(head -c 300 "$name.err")"; continue
  fi
  LD_LIBRARY_PATH="$prefix/lib" ./"$name" >"$name.txt" 2>"$name.err"
  rc=$?
  if [ $rc -eq 0 ] && LD_LIBRARY_PATH="$prefix/lib" ldd "./$name" | grep -q "libwhirl.so.$major => $prefix/lib/" \
     && same_output "$repo/examples/$name.out" "$name.txt"; then
    pass "example $name: built with pkg-config, runs on $prefix/lib/libwhirl.so.$major, output as examples/$name.out"
  else
    fail "example $name (exit $rc): $(diff "$repo/examples/$name.out" "$name.txt" | head -5 | tr '\n' ' ') $(head -c 200 "$name.err")"
  fi
done
if [ $nex -ge 2 ]; then pass "$nex examples"; else fail "only $nex examples in examples/"; fi
# one example linked against libwhirl.a: needs no libwhirl.so and prints the same
first=$(ls "$repo"/examples/*.c | head -n 1)
name=$(basename "$first" .c)
if cc -std=c11 -o "$name.static" "$name.c" $(pkg-config --cflags whirl) \
      $(pkg-config --static --libs whirl | sed 's/-lwhirl\b/-l:libwhirl.a/') 2>"$name.err" \
   && ! ldd "./$name.static" | grep -q libwhirl && ./"$name.static" >"$name.static.txt" \
   && same_output "$repo/examples/$name.out" "$name.static.txt"; then
  pass "example $name linked statically (pkg-config --static) prints the same"
else fail "example $name statically: $(head -c 300 "$name.err")"; fi
# a C++ program: the headers' extern "C" guards give the library's C names, so g++ links
cat >cxx_link.cpp <<'EOF'
#include <cstdio>
#include <whirl.h>
int main()
{
    whirl_shape_info info;
    if (whirl_continuum_solve(3.5, 2, 0.0, 0.0, &info) != GSL_SUCCESS) {
        std::printf("%s\n", whirl_last_error());
        return 1;
    }
    std::printf("%s %.6f\n", whirl_version(), info.tip_r);
    return 0;
}
EOF
if ! command -v g++ >/dev/null; then fail "C++ link: no g++ (build-essential)"
elif g++ -std=c++11 -Wall -Wextra -Werror cxx_link.cpp $cflags $libs -o cxx_link 2>cxx.err \
   && out=$(LD_LIBRARY_PATH="$prefix/lib" ./cxx_link) \
   && [ "$out" = "$version 0.230209" ]; then
  pass "a C++ program (g++ -std=c++11) includes <whirl.h>, links and runs: $out"
else fail "C++ link: $(head -c 300 cxx.err) $out"; fi
# the installed program names the installed scenes and example data, and they run
if "$prefix/bin/whirl" simulate --help | grep -qF "$prefix/share/whirl/scenes" \
   && "$prefix/bin/whirl" fit --help | grep -qF "$prefix/share/whirl/fit_example.csv" \
   && grep -qF "$prefix/share/whirl" man.txt \
   && "$prefix/bin/whirl" simulate "$prefix/share/whirl/scenes/mode2.ini" --set run.t_end=0.1 >/dev/null \
   && PATH="$prefix/bin:$PATH" eval "$("$prefix/bin/whirl" fit --help | sed -n '/^example:/{n;p;}')" >/dev/null; then
  pass "whirl simulate --help, whirl fit --help and whirl(1) name $prefix/share/whirl; its examples run"
else fail "installed data directory: $("$prefix/bin/whirl" simulate --help | head -2 | tr '\n' ' ')"; fi
for key in dim links t_end method stop_deviation reference_mode; do
  grep -q "$key" man.txt || { fail "whirl(1) lacks the scene key $key"; key=""; break; }
done
[ -n "$key" ] && pass "whirl(1) lists the scene keys"
cd "$repo" || exit 1

# ---- staging with DESTDIR, uninstall ----
if mk install DESTDIR="$tmp/stage" PREFIX=/opt/whirl >/dev/null 2>"$tmp/stage.err" \
   && [ -x "$tmp/stage/opt/whirl/bin/whirl" ] && [ -f "$tmp/stage/opt/whirl/include/whirl/common.h" ] \
   && grep -qx 'prefix=/opt/whirl' "$tmp/stage/opt/whirl/lib/pkgconfig/whirl.pc" \
   && [ -z "$(find "$tmp/stage" -mindepth 1 -maxdepth 1 ! -name opt)" ]; then
  pass "make install DESTDIR=... PREFIX=/opt/whirl: staged, whirl.pc says /opt/whirl"
else fail "DESTDIR install: $(head -c 300 "$tmp/stage.err")"; fi
if mk uninstall DESTDIR="$tmp/stage" PREFIX=/opt/whirl >/dev/null 2>&1 \
   && [ -z "$(find "$tmp/stage" ! -type d)" ]; then pass "make uninstall DESTDIR=...: no file left"
else fail "uninstall left: $(find "$tmp/stage" ! -type d | head -3 | tr '\n' ' ')"; fi
if mk uninstall PREFIX="$prefix" >/dev/null 2>&1 && [ -z "$(find "$prefix" ! -type d)" ]; then
  pass "make uninstall PREFIX=...: no file left"
else fail "uninstall left: $(find "$prefix" ! -type d | head -3 | tr '\n' ' ')"; fi

# ---- an unwritable prefix: one clear error, nothing written ----
: >"$tmp/afile"
mk install PREFIX="$tmp/afile/prefix" >"$tmp/bad.out" 2>"$tmp/bad.err"
rc=$?
if [ $rc -ne 0 ] && grep -q "make install: cannot write to $tmp/afile/prefix/bin" "$tmp/bad.err" \
   && [ ! -s "$tmp/afile" ]; then
  pass "unwritable prefix: make fails with \"$(head -n 1 "$tmp/bad.err" | cut -c1-60)...\""
else fail "unwritable prefix (rc $rc): $(head -c 300 "$tmp/bad.err")"; fi
if mk install PREFIX=relative/path >/dev/null 2>"$tmp/bad.err"; then fail "relative PREFIX accepted"
elif grep -q "PREFIX must be an absolute path" "$tmp/bad.err"; then pass "relative PREFIX refused"
else fail "relative PREFIX: $(head -c 300 "$tmp/bad.err")"; fi
# the program in BUILD names the default data directory again (the installs above compiled in
# theirs)
if mk all >"$tmp/rebuild.out" 2>&1 && "$build/whirl" simulate --help | grep -q "/usr/local/share/whirl"; then
  pass "make all after the installs: whirl names /usr/local/share/whirl again"
else fail "rebuild after the installs: $(tail -n 3 "$tmp/rebuild.out")"; fi
finish
