# SPDX-License-Identifier: MIT
# CDF of the 20 Hz cycle latency per T_B, one sensor and configuration,
# office (indoor) and forest side by side, percentile points marked, the
# 50 ms budget as a vertical line (like the paper's figure).
#
#   gnuplot -e "dir='<results>'; sensor='mid360'; config='carc'; title='...'; out='docs/img/x.png'" \
#           bench/latency/plot_cdf.gp
# Reads <dir>/cdf/<sensor>-<scene>-<config>-tb<T_B>.dat (latency_ms fraction)
# and <dir>/pct/... (latency_ms fraction label), written by bench_latency.
# A missing T_B is skipped.

if (!exists("title")) title = sensor . " " . config
set terminal pngcairo size 1400,560 font "DejaVu Sans,11"
set output out
set multiplot layout 1,2 title title
set logscale x
set xlabel "cycle latency [ms] (log)"
set ylabel "fraction of cycles"
set yrange [0:1.02]
set key bottom right
set grid
set arrow 1 from 50, graph 0 to 50, graph 1 nohead dashtype 2 linewidth 2 linecolor rgb "#c00000"
set label 1 "50 ms budget" at 50, graph 0.05 offset 0.5,0 textcolor rgb "#c00000"
windows = "0.1 0.2 0.3 0.4 0.5"
do for [scene in "office forest"] {
  set title (scene eq "office" ? "indoor (office)" : "forest")
  plot for [i=1:words(windows)] \
         sprintf("%s/cdf/%s-%s-%s-tb%s.dat", dir, sensor, scene, config, word(windows, i)) \
         using 1:2 with lines linewidth 2 linecolor i title sprintf("T_B = %s s", word(windows, i)), \
       for [i=1:words(windows)] \
         sprintf("%s/pct/%s-%s-%s-tb%s.dat", dir, sensor, scene, config, word(windows, i)) \
         using 1:2 with points pointtype 7 pointsize 0.8 linecolor i notitle
}
unset multiplot
