#!/bin/sh
# The programs in examples/: each compiled as a user would (the public headers and the built
# library only, no src/), run, and required to exit 0 and print PASS (each checks its own result
# against something independent; see its header). Under the sanitizers they are built with them.
. "$(dirname "$0")/lib.sh"
root="$(dirname "$0")/.."
lib="$(dirname "$WHIRL")/libwhirl.a"
flags=""
[ "${WHIRL_SANITIZE:-0}" = 1 ] && flags="-fsanitize=address,undefined -fno-omit-frame-pointer"
for src in "$root"/examples/*.c; do
  name=$(basename "$src" .c)
  if ${CC:-cc} -std=c11 -Wall -Wextra -Werror $flags -I"$root/include" "$src" "$lib" \
       $(pkg-config --cflags --libs gsl nlopt inih lapacke) -llapack -lblas -lpthread -fopenmp -lm \
       -o "$tmp/$name" 2>"$tmp/cc.err"; then
    pass "example $name compiles"
  else fail "example $name compiles ($(head -c 300 "$tmp/cc.err"))"; fi
  if "$tmp/$name" >"$tmp/out" 2>"$tmp/err" && [ "$(tail -n 1 "$tmp/out")" = PASS ]; then
    pass "example $name checks its result"
  else fail "example $name checks its result ($(tail -n 2 "$tmp/out") $(head -c 300 "$tmp/err"))"; fi
done
finish
