# Animates a trace (`whirl simulate` [output] trace, `whirl regime --trace`): one frame per block
# (the pivot, then every mass; columns x y z t, inertial frame). The view is true to scale: the
# same scale on all three axes (a planar trace, y = 0 throughout, is drawn in the x-z plane with
# equal axes). The rotation axis is drawn dashed, the pivot's circle (radius eps, from the
# trace's "# trace:" line) in orange; the title names the links, the rate (and in SI units its
# frequency in Hz), eps and the drag when not zero, and the time, with their units (from the
# "# units:" line). The frames are drawn as PNG and made into the movie by ffmpeg, cropped to
# what is drawn (ffmpeg's cropdetect over all frames): .mp4 (H.264), .webm (VP9) or .gif (a
# palette of 16 colours: a few hundred kB for 5 s).
# usage: gnuplot -e "trace='run.dat'; out='run.mp4'" plots/animate.gp   (or out='run.gif', .webm)
# optional: step=K (every K-th block), delay=D (hundredths of a second per frame), width=W
#           (pixels of the movie), view='70,30' (gnuplot's set view), mp4='run.mp4' (a second
#           movie, MP4); box_w=W, box_h=H (the frames fit in W x H pixels, text scaled with
#           them), present=1 (text 1.5 times larger), slow=F (the movie's time runs F times
#           slower than the trace's: the frame rate from the blocks' spacing, at most 50 a
#           second, blocks skipped above; instead of delay).
if (!exists("trace")) { print "usage: gnuplot -e \"trace='run.dat'; out='run.gif'\" plots/animate.gp"; exit status 1 }
load system("dirname '".ARG0."'")."/style.gp"
set datafile separator whitespace
if (!exists("out")) { out = trace . ".gif" }
if (!exists("step")) { step = 1 }
if (!exists("delay")) { delay = 4 }
# slow motion: the frame rate from the time between two blocks (column 4), at most 50 a second
if (exists("slow")) {
    stats trace index 0 using 4 nooutput
    t0 = STATS_min
    stats trace index 1 using 4 nooutput
    dtb = STATS_min - t0
    if (!(dtb > 0)) { print "animate.gp: ".trace.": the blocks' times do not increase"; exit status 1 }
    step = ceil(1.0 / (dtb * slow * 50) - 1e-9)
    step = step < 1 ? 1 : step
    delay = 100 * dtb * step * slow
}
if (!exists("width")) { width = 640 }
if (!exists("view")) { view = "70,30" }

max(a, b) = a > b ? a : b
min(a, b) = a < b ? a : b
omega = meta(trace, "omega"); eps_s = meta(trace, "eps"); links = meta(trace, "links")
drag = meta(trace, "drag"); drag2 = meta(trace, "drag_quadratic")
eps = eps_s eq "" ? 0 : real(eps_s)
ul = u_len(trace); ut = u_time(trace); ur = u_rate(trace)
w = real(omega)
caption = sprintf("%s links, omega = %.4g %s", links, w, ur) . (physical(trace) ? sprintf(" (%.3g Hz)", w / (2 * pi)) : "")
nl = "\n"
# eps and the drag, when not zero, on a second line
extra = eps != 0 ? sprintf("eps = %.3g %s", eps, ul) : ""
if (real(drag) != 0 || real(drag2) != 0) { extra = extra . (strlen(extra) > 0 ? ", " : "") . sprintf("drag C = %.3g, C2 = %.3g", real(drag), real(drag2)) }
if (strlen(extra) > 0) { caption = caption . nl . extra }

# extent of the whole run, so that the axes stay fixed
stats trace using 1 nooutput
nblocks = STATS_blocks
xmin = STATS_min; xmax = STATS_max
stats trace using 2 nooutput
ymin = STATS_min; ymax = STATS_max
stats trace using 3 nooutput
zmin = STATS_min; zmax = STATS_max
R = 1.08 * max(max(max(abs(xmin), abs(xmax)), max(abs(ymin), abs(ymax))), eps)
R = R > 0 ? R : 0.1
ztop = max(zmax, 0) + 0.06 * (max(zmax, 0) - zmin)
zbot = zmin - 0.06 * (max(zmax, 0) - zmin)
planar = (ymin == 0 && ymax == 0)

# a round tick step (style.gp), ticks within +-R only
# (the outermost ticks within 0.8 R: labels at the box's corners collide)
tstep = nice(R / 1.2)
if (floor(0.8 * R / tstep) < 1) { tstep = nice(R / 2.5) }
tend = floor(0.8 * R / tstep) * tstep

unset key
set style line 11 lc rgb "#999999" dt 2 lw 1
set style line 12 lc rgb "#e67e22" lw 1.5
set samples 100
set xlabel "x [".ul."]"
set xtics -tend, tstep, tend
if (planar) {
    set size ratio -1
    set xrange [-R:R]
    set yrange [zbot:ztop]
    set ylabel "z [".ul."]"
    set arrow 1 from 0, zbot to 0, ztop nohead ls 11
    if (eps > 0) { set arrow 2 from -eps, 0 to eps, 0 nohead ls 12 }
} else {
    set view @view, 1.0
    set view equal xyz
    set xrange [-R:R]
    set yrange [-R:R]
    set zrange [zbot:ztop]
    set xyplane at zbot
    set ytics -tend, tstep, tend
    set ylabel "y [".ul."]"
    # along the z axis, left of its tick labels (norotate at a fixed offset fell on a tick in a
    # tall frame)
    set zlabel "z [".ul."]" rotate parallel
    set lmargin 8
    set arrow 1 from 0, 0, zbot to 0, 0, ztop nohead ls 11
    # the pivot's circle, as data
    set print $circle
    do for [k = 0:64] { print sprintf("%.6g %.6g 0", eps * cos(2 * pi * k / 64), eps * sin(2 * pi * k / 64)) }
    set print
    ztext = ztop + 0.14 * (ztop - zbot)
}
# one frame: block i, with its time
if (planar) {
    draw = "stats [*:*][*:*] trace index i using 4 nooutput; set title sprintf('%s%st = %.2f %s', caption, nl, STATS_min, ut) font sprintf(',%g', 12 * fs * zoom); plot trace index i using 1:3 with linespoints lt 1 pt 7 ps 0.6 * fs * zoom"
} else {
    draw = "stats [*:*][*:*] trace index i using 4 nooutput; set label 2 sprintf('%s%st = %.2f %s', caption, nl, STATS_min, ut) at 0, 0, ztext center offset 0, 1 font sprintf(',%g', 12 * fs * zoom); splot trace index i using 1:2:3 with linespoints lt 1 pt 7 ps 0.5 * fs * zoom, $circle using 1:2:3 with lines ls 12"
}

# the frames at the movie's width (then cropped)
# a tall chain (its height over its diameter, aspect) a taller canvas, up to 1.6 times its width:
# the 3D box fits, the crop takes the rest
aspect = (ztop - zbot) / (2 * R)
tall = planar ? 1.0 : min(1.6, max(1.15, 0.8 * aspect))
# the box the frames fit in (style.gp's box_w, box_h): the width that fills it
# (drawn at twice that, the crop then scaled to fill the box: the drawing of a chain covers about
# half of its frame, and a crop scaled up would blur)
boxed = box_w > 0 || box_h > 0
if (boxed) { width = 2 * int(box_w > 0 && box_h > 0 ? min(box_w, box_h / tall) : box_w > 0 ? box_w : box_h / tall) }
width = 2 * int(width / 2)
height = int(width * tall)
# the text and lines with the frame (11 pt at 640 px) and fs (style.gp: 1.5 to present)
zoom = width / 640.0
# taller still: the whole 3D box drawn smaller (its height at scale 1 is about 0.8 aspect widths)
if (!planar) { set view @view, min(1.0, 1.6 / (0.8 * aspect)) }
frames = system("mktemp -d")
set terminal pngcairo enhanced font sprintf("DejaVu Sans,%g", 11 * fs * zoom) linewidth 1.3 * fs * zoom background rgb "white" size width, height
k = 0
do for [i = 0:nblocks - 1:step] {
    set output sprintf("%s/f%05d.png", frames, k)
    @draw
    k = k + 1
}
set output
# the box holding every frame's drawing (cropdetect on the negated frames: white is the border),
# a margin of 8 px around it, even sizes
crop = system(sprintf("ffmpeg -loglevel info -framerate 25 -i '%s/f%%05d.png' -vf negate,cropdetect=limit=1:round=2:reset=0 -f null - 2>&1 | grep -o 'crop=[0-9:]*' | tail -1 | awk -F'[=:]' -v W=%d -v H=%d '{ x = $4 - 8; y = $5 - 8; if (x < 0) x = 0; if (y < 0) y = 0; w = $2 + 16; h = $3 + 16; if (x + w > W) w = W - x; if (y + h > H) h = H - y; printf \"crop=%%d:%%d:%%d:%%d,\", w - w %% 2, h - h %% 2, x, y }'", frames, width, height))
fps = 100.0 / delay
scale = "scale=trunc(iw/2)*2:trunc(ih/2)*2"
# the box: the cropped frames scaled to fit it (16384 px: a side left free)
if (boxed) { scale = sprintf("scale=w=%d:h=%d:force_original_aspect_ratio=decrease:flags=lanczos,", box_w > 0 ? box_w : 16384, box_h > 0 ? box_h : 16384) . scale }
# movie(file): the ffmpeg command for a file, by its extension
movie(f) = f[strlen(f) - 3:] eq ".gif" ? \
    sprintf("ffmpeg -loglevel error -y -framerate %g -i '%s/f%%05d.png' -vf '%s%s,split[a][b];[a]palettegen=max_colors=16:stats_mode=diff[p];[b][p]paletteuse=dither=none:diff_mode=rectangle' -f gif '%s' && echo ok", fps, frames, crop, scale, f) : \
  f[strlen(f) - 4:] eq ".webm" ? \
    sprintf("ffmpeg -loglevel error -y -framerate %g -i '%s/f%%05d.png' -vf '%s%s' -c:v libvpx-vp9 -b:v 0 -crf 40 -deadline realtime -cpu-used 8 -pix_fmt yuv420p -f webm '%s' && echo ok", fps, frames, crop, scale, f) : \
    sprintf("ffmpeg -loglevel error -y -framerate %g -i '%s/f%%05d.png' -vf '%s%s' -c:v libx264 -crf 23 -pix_fmt yuv420p -movflags +faststart -f mp4 '%s' && echo ok", fps, frames, crop, scale, f)
rc = system(movie(out))
rc2 = exists("mp4") ? system(movie(mp4)) : "ok"
system(sprintf("rm -r '%s'", frames))
if (rc ne "ok") { print "animate.gp: ffmpeg failed for ".out; exit status 1 }
if (rc2 ne "ok") { print "animate.gp: ffmpeg failed for ".mp4; exit status 1 }
