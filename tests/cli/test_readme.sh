#!/bin/sh
# The README's command table (| `whirl CMD` | what it computes | manual |) against the program:
# every command `whirl --help` lists has its row, every row names a command the program has, and
# each row's manual links are pages that exist.
. "$(dirname "$0")/lib.sh"
root=$(cd "$(dirname "$0")/../.." && pwd)
readme=$root/README.md
"$WHIRL" --help | awk '/^commands:/ { on = 1; next } on && NF { print $1 }' | sort >"$tmp/commands"
grep -o '^| `whirl [a-z]*` |' "$readme" | sed 's/^| `whirl \([a-z]*\)` |$/\1/' | sort >"$tmp/rows"
[ "$(wc -l <"$tmp/commands")" -ge 10 ] && pass "whirl --help lists $(wc -l <"$tmp/commands") commands" ||
  fail "whirl --help lists $(wc -l <"$tmp/commands") commands"
missing=$(comm -23 "$tmp/commands" "$tmp/rows" | tr '\n' ' ')
[ -z "$missing" ] && pass "README: a row for every command" || fail "README: no row for: $missing"
extra=$(comm -13 "$tmp/commands" "$tmp/rows" | tr '\n' ' ')
[ -z "$extra" ] && pass "README: no row for a command the program lacks" || fail "README: rows without a command: $extra"
dead=
for link in $(grep '^| `whirl [a-z]*` |' "$readme" | grep -o '](docs/[^)]*)' | sed 's/^](//; s/)$//'); do
  [ -f "$root/$link" ] || dead="$dead $link"
done
[ -z "$dead" ] && pass "README: the command table's manual links exist" || fail "README: dead links:$dead"
finish
