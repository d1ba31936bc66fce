#!/bin/sh
# The Debian package of `make deb` as a user meets it, as TAP: installed with apt-get (which
# fetches its dependencies), the README's first recipe run with /usr/bin/whirl and the scenes of
# /usr/share/whirl, the manual page, pkg-config and a C example built against the installed
# library, then the package removed (purged) and nothing of it left. It installs into the system:
# run it as root, by hand, on a machine where no other whirl is installed in /usr (not part of
# make check):
#   make deb && sh tests/tools/deb_test.sh [build/whirl_VERSION-1_ARCH.deb]
cd "$(dirname "$0")/../.." || exit 1
root=$(pwd)
deb=${1:-$(ls build/whirl_*.deb 2>/dev/null | tail -1)}
[ -f "$deb" ] || { echo "deb_test: no package (make deb first)" >&2; exit 1; }
case $deb in /*) ;; *) deb=$root/$deb ;; esac
[ "$(id -u)" -eq 0 ] || { echo "deb_test: run as root (apt-get install)" >&2; exit 1; }
if [ -e /usr/bin/whirl ] && ! dpkg -S /usr/bin/whirl 2>/dev/null | grep -q '^whirl:'; then
  echo "deb_test: /usr/bin/whirl exists and is not the whirl package's: not touched" >&2; exit 1
fi
WHIRL=/usr/bin/whirl
. tests/cli/lib.sh
cd "$tmp" || exit 1

if apt-get install -y --no-install-recommends "$deb" >"$tmp/apt.log" 2>&1; then
  pass "apt-get install $(basename "$deb")"
else fail "apt-get install: $(tail -3 "$tmp/apt.log")"; finish; fi
echo "# $(grep -c '^Setting up' "$tmp/apt.log") packages set up: $(grep '^Setting up' "$tmp/apt.log" | cut -d' ' -f3 | tr '\n' ' ')"
version=$(dpkg-query -W -f='${Version}' whirl)
"$WHIRL" --version | grep -q "^whirl ${version%-*}" && pass "whirl --version: ${version%-*}" ||
  fail "whirl --version: $("$WHIRL" --version | head -1)"
ldd "$WHIRL" | grep -q 'libmpi' && fail "/usr/bin/whirl links Open MPI" || pass "/usr/bin/whirl without Open MPI"
"$WHIRL" simulate --help | grep -q 'examples in /usr/share/whirl/scenes' &&
  pass "the program names /usr/share/whirl" || fail "the program's data folder: $("$WHIRL" simulate --help | head -2)"

# the README's first recipe, the scene from the package
expect_ok "README 1: shape --plot shapes.png" shape --length 60cm --mass 50g --omega 2Hz,4Hz,6Hz \
  --mode 2 --plot shapes.png
[ "$(head -c 8 shapes.png | od -An -c | tr -d ' ')" = '211PNG\r\n032\n' ] && pass "shapes.png is a PNG" ||
  fail "shapes.png is not a PNG"
expect_ok "README 1: simulate classroom.ini --animate run.mp4" simulate \
  /usr/share/whirl/scenes/classroom.ini --set start.omega=4Hz --animate run.mp4
info=$(ffprobe -v error -select_streams v:0 -count_frames -show_entries \
  stream=codec_name,nb_read_frames -of csv=p=0 run.mp4 2>&1)
[ "$info" = "h264,126" ] && pass "run.mp4: H.264, 126 frames (5 s at 25 a second)" || fail "run.mp4: $info"
"$WHIRL" critical --modes 3 --length 60cm --mass 50g | grep -v '^#' >critical.csv
printf 'mode,omega\n1,4.86114186789534\n2,11.158348982982675\n3,17.492744509557543\n' >want.csv
cmp -s critical.csv want.csv && pass "README 1: the critical rates as printed there" ||
  fail "critical rates: $(tr '\n' ' ' <critical.csv)"

# the manual page, pkg-config, a C program against the installed library
zcat /usr/share/man/man1/whirl.1.gz | grep -q '^\.TH WHIRL 1' && pass "man page whirl(1)" ||
  fail "man page: $(zcat /usr/share/man/man1/whirl.1.gz | head -2)"
[ "$(pkg-config --modversion whirl 2>&1)" = "${version%-*}" ] && pass "pkg-config --modversion whirl" ||
  fail "pkg-config: $(pkg-config --modversion whirl 2>&1)"
# (building against it needs the -dev packages of GSL, NLopt, inih, LAPACKE, as pkg-config says)
if cc "$root/examples/steady_shape.c" $(pkg-config --cflags --libs whirl) -lm -o prog 2>cc.err &&
   ./prog >prog.out 2>&1 && ldd ./prog | grep -q 'libwhirl.so.2 => /\(usr/\)\?lib/'; then
  pass "examples/steady_shape.c built with pkg-config, run against the package's libwhirl.so.2"
else fail "example against the package: $(head -c 300 cc.err) $(head -c 300 prog.out)"; fi

# removed: nothing left
if apt-get remove --purge -y whirl >"$tmp/remove.log" 2>&1 && ! dpkg -s whirl >/dev/null 2>&1 \
   && [ ! -e /usr/bin/whirl ] && [ ! -e /usr/share/whirl ] && [ ! -e /usr/include/whirl ] \
   && [ -z "$(ls /usr/lib/*/libwhirl* 2>/dev/null)" ]; then
  pass "apt-get remove --purge whirl: nothing left"
else fail "remove: $(tail -2 "$tmp/remove.log")"; fi
finish
