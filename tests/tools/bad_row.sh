#!/bin/sh
# bad_row.sh IN OUT KIND: copies the CSV IN to OUT with its first data row (the first line that
# starts with a digit) spoiled: KIND nan, inf or 1e999 in column 8, or cut (the first 5 columns
# only). For the tests of --resume, which must refuse such a file.
awk -F, -v kind="$3" 'BEGIN { OFS = "," }
  !done && /^[0-9]/ { done = 1; if (kind == "cut") { NF = 5 } else { $8 = kind }; print; next }
  { print }' "$1" >"$2"
