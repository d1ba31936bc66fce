# The style every figure of plots/ shares: pngcairo, one palette, a light grid, and the units of
# a CSV or trace read from its "# units:" comment line (written by every whirl command):
#   # units: dimensionless (length L, ...)          -> L, sqrt(g/L), sqrt(L/g), M g
#   # units: length=m mass=kg time=s rate=rad/s ...  -> m, rad/s, s, N
# A script loads it with: load system("dirname '".ARG0."'")."/style.gp"
# and opens its output with: set terminal @term size W*px, H*px   (W, H in pixels)
# The terminal follows the output's extension (out='fig.svg'), or fmt='png', 'svg' or 'pdf':
# pngcairo, svg or pdfcairo (PDF sizes in points: px = 1/72 inch, so that text and lines keep
# their size relative to the figure).
if (!exists("fmt")) { fmt = exists("out") && strlen(out) > 4 ? out[strlen(out) - 2:] : "png" }
px = 1
term = 'pngcairo enhanced font "DejaVu Sans,11" linewidth 1.3 background rgb "white"'
if (fmt eq "svg") { term = 'svg enhanced font "DejaVu Sans,11" linewidth 1.3 background rgb "white"' }
if (fmt eq "pdf") { term = 'pdfcairo enhanced font "DejaVu Sans,11" linewidth 1.3 background rgb "white"'; px = 1.0 / 72 }
# The picture's size and text (whirl plot --size, --present), for the figures that open their
# output with: cw = W; ch = H; @canvas   (W x H: the figure's own size in pixels)
#   box_w, box_h  the box the picture fits in, in pixels (0: that side free; both 0: W x H), the
#                 whole figure scaled by one factor, zoom (its proportions kept, true to scale)
#   present = 1   text and lines 1.5 times larger against the figure (fs), for a room: the
#                 layout of a figure of plot.gp counts its margins in fs-scaled pixels
if (!exists("box_w")) { box_w = 0 }
if (!exists("box_h")) { box_h = 0 }
if (!exists("present")) { present = 0 }
fs = present ? 1.5 : 1.0
fit_zoom(w, h) = box_w > 0 && box_h > 0 ? (box_w * h < box_h * w ? real(box_w) / w : real(box_h) / h) : \
                 box_w > 0 ? real(box_w) / w : box_h > 0 ? real(box_h) / h : 1.0
px_unit = px
canvas = 'zoom = fit_zoom(cw, ch); px = px_unit * zoom; set terminal ' . \
         (fmt eq "svg" ? "svg" : fmt eq "pdf" ? "pdfcairo" : "pngcairo") . \
         ' enhanced font sprintf("DejaVu Sans,%g", 11 * fs * zoom) linewidth 1.3 * fs * zoom background rgb "white" size cw * px, ch * px'
set linetype 1 lc rgb "#1f4e9c" lw 2 pt 7
set linetype 2 lc rgb "#c0392b" lw 2 pt 5
set linetype 3 lc rgb "#1e8449" lw 2 pt 9
set linetype 4 lc rgb "#7d3c98" lw 2 pt 11
set linetype 5 lc rgb "#b9770e" lw 2 pt 13
set linetype 6 lc rgb "#117a8b" lw 2 pt 15
set linetype cycle 6
set grid lc rgb "#dddddd" lw 1
set datafile separator ","
set key noenhanced
set format "%g"
# units of a file (f: its path)
physical(f) = int(system(sprintf("grep -c -m 1 '^# units: length=m' '%s'", f))) > 0
u_rate(f) = physical(f) ? "rad/s" : "sqrt(g/L)"
u_len(f) = physical(f) ? "m" : "L"
u_time(f) = physical(f) ? "s" : "sqrt(L/g)"
u_force(f) = physical(f) ? "N" : "M g"
# lines of comments and header before the first data row of a CSV
skip_of(f) = int(system(sprintf("grep -n -m 1 -v '^#' '%s' | cut -d: -f1", f)))
# the value of key=... on the first comment line that has it ("" if none)
meta(f, key) = system(sprintf("grep -m 1 -o '[ #]%s=[^ ,;]*' '%s' | head -1 | cut -d= -f2", key, f))
# the rate of a file as its writer gave it, from its "# rate: " line up to " (" ("4 Hz
# (omega=25.13 rad/s)" -> "4 Hz", "omega=3 sqrt(g/L)" whole), else omega=W with its unit; short
# (4 significant digits)
rate_text(f) = system(sprintf("sed -n '/^# rate: /{s/^# rate: //;s/ (.*//;p;q}' '%s'", f))
rate_label(f) = strlen(rate_text(f)) > 0 ? rate_text(f) : sprintf("omega = %.4g %s", real(meta(f, "omega")), u_rate(f))
# a round tick step near x > 0: 1, 2 or 5 times a power of ten (set ytics nice(span / 4): four or
# five labelled ticks, whatever the panel's height)
nice(x) = (nice_m = x / 10**floor(log10(x)), (nice_m < 1.5 ? 1 : nice_m < 3.5 ? 2 : nice_m < 7.5 ? 5 : 10) * 10**floor(log10(x)))
