#!/bin/sh
# Writes the manual page whirl(1) on stdout, generated from the program's own help: the overview
# of `whirl --help`, then for every command its `whirl CMD --help` (usage line, description,
# options, examples), so the page cannot drift from the program; the scene files' keys from the
# opening comment of include/whirl/scene.h; DATADIR, where make install puts the scenes and plot
# scripts. Usage: man.sh PROGRAM DATADIR
set -e
whirl=${1:?usage: man.sh PROGRAM DATADIR}
datadir=${2:?usage: man.sh PROGRAM DATADIR}
scene_h="$(dirname "$0")/../include/whirl/scene.h"
version=$("$whirl" --version | sed -n 's/^whirl \([^ ]*\).*/\1/p')
[ -n "$version" ] || { echo "man.sh: no version from $whirl --version" >&2; exit 1; }
"$whirl" --help >/dev/null

# roff: backslashes, leading dots and quotes, and hyphens escaped
esc() { sed -e 's/\\/\\e/g' -e "s/^\\([.']\\)/\\\\\\&\\1/" -e 's/-/\\-/g'; }

cat <<END
.TH WHIRL 1 "" "whirl $version" "User Commands"
.SH NAME
whirl \\- steady shapes, dynamics and stability of a chain spun about the vertical axis
.SH SYNOPSIS
.B whirl
.I COMMAND
.RI [ OPTIONS ]
.br
.B whirl
.I COMMAND
.B \\-\\-help
.br
.B whirl \\-\\-version
.SH DESCRIPTION
END
# the overview: the lines of `whirl --help` between the usage lines and "commands:"
"$whirl" --help | sed -n '/^$/,/^commands:/p' | sed '/^commands:/d; /^$/d' | esc
cat <<'END'
.PP
Every command takes \fB\-o\fR \fIFILE\fR (written atomically: a failed run leaves no file) and
\fB\-\-help\fR; bad input gives a one\-line error naming the problem and a non\-zero exit.
.SH COMMANDS
END
"$whirl" --help | sed -n '/^commands:/,$p' | sed 1d | while read -r cmd summary; do
  [ -n "$cmd" ] || continue
  echo ".SS whirl $cmd"
  # the help: "usage: ..." first, prose, then sections "NAME:" at the margin; in "options:" the
  # lines "  OPTION ARG   text" (text from column 30), in other sections indented lines verbatim
  "$whirl" "$cmd" --help | esc | awk '
    NR == 1 { sub(/^usage: /, ""); print ".nf"; print; print ".fi"; next }
    /^$/ { next }
    /^[^ ].*:$/ { section = $0; print ".PP"; print "\\fB" $0 "\\fR"; next }
    section == "options:" && /^  \\-/ {
      left = substr($0, 3, 26); sub(/ +$/, "", left); text = substr($0, 30); sub(/^ +/, "", text)
      n = split(left, w, " "); line = ""
      # option names bold, their arguments italic
      for (i = 1; i <= n; i++)
        line = line (i > 1 ? " " : "") "\\f" (substr(w[i], 1, 2) == "\\-" ? "B" : "I") w[i] "\\fR"
      print ".TP"; print line; print text; next }
    section != "" && section != "options:" && /^ / { sub(/^ +/, ""); print ".nf"; print "  " $0; print ".fi"; next }
    { sub(/^ +/, ""); print; print ".br" }'
done
cat <<'END'
.SH SCENE FILES
A scene (\fBwhirl simulate\fR \fISCENE\fR) is an INI file; examples are installed in
END
echo ".I $(echo "$datadir/scenes" | esc)"
cat <<'END'
(data/scenes in the source tree). Its sections and keys, from <whirl/scene.h>:
.PP
.nf
END
# the key list of the header's opening comment: from "[units]" to the line before "Syntax"
awk 'NR == 1, /\*\// { print }' "$scene_h" | sed -n '/\[units\]/,/^ \* *$/p' | sed '$d' |
  sed 's/^ \* \{0,1\}//' | esc
cat <<'END'
.fi
.PP
Overrides \fB\-\-set\fR \fIsection.key=value\fR replace or add keys after the file.
.SH UNITS
Dimensionless unless a command says otherwise: chain length L = 1, chain mass M = 1, gravity
g = 1; rates in sqrt(g/L), times in sqrt(L/g), tensions in M g. z points up; the pivot is the
origin, on the rotation axis. Mode k has k nodes: the pivot plus k\-1 crossings of the axis.
With \fB\-\-length\fR, \fB\-\-mass\fR or \fB\-\-gravity\fR a command works in SI units
(m, kg, s, rad/s, N; rates also as 4Hz or 240rpm), its CSV says so on a "# units:" line, and its
error messages give their rates and tip radii in those units.
.SH OUTPUT
CSV: comment lines start with #, the first other line is the header, numbers with full
precision.
.SH ENVIRONMENT
.TP
.B WHIRL_PROGRESS_AFTER
Seconds after which \fBshape\fR and \fBsweep\fR show their progress line on a terminal
(default 1; 0 shows it from the first report).
.TP
.B OMP_NUM_THREADS
Threads of the commands that run on several cores.
.SH FILES
.TP
END
echo "$datadir" | esc
cat <<'END'
The example scenes (scenes/), the gnuplot scripts (plots/) and the fit's example data
(fit_example.csv, in cm).
.SH EXIT STATUS
0 on success, 130 when interrupted (Ctrl\-C; the rows written so far are kept), non\-zero on
any error.
.SH SEE ALSO
The C library libwhirl (\fBpkg\-config \-\-cflags \-\-libs whirl\fR, header \fI<whirl.h>\fR)
and the README of the source tree.
END
