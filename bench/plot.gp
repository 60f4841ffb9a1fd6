# Plots of a `photovr bench` run, from its CSV files:
#   gnuplot -e "dir='out/bench'" bench/plot.gp
# bench_error_vs_time.png: relMSE against accumulated wall time, log-log, one panel per
#   scene, one curve per scored configuration (bench.csv: one row per frame).
# bench_stages.png: mean stage times per frame of every configuration at the scored size,
#   stacked (bench_configs.csv: one row per configuration).
if (!exists("dir")) dir = "out/bench"
frames = dir."/bench.csv"
configs = dir."/bench_configs.csv"
set datafile separator ","
set datafile missing ""
set key noenhanced
set termoption noenhanced

# Columns of bench_configs.csv: 1 label, 2 short, 3 scene, 10 width, 13 scored.
scenes = system("awk -F, 'NR > 1 && $13 == 1 { print $3 }' ".configs." | uniq")
labelsOf(s) = system("awk -F, -v s=".s." 'NR > 1 && $13 == 1 && $3 == s { print $1 }' ".configs)
shortOf(l) = system("awk -F, -v l=".l." '$1 == l { print $2 }' ".configs)

set terminal pngcairo size 1200,420 font ",8"
set output dir."/bench_error_vs_time.png"
set multiplot layout 1, words(scenes) title "relMSE against wall time (1 spp per frame unless named)"
set logscale xy
set xlabel "accumulated wall time (ms)"
set ylabel "relMSE"
set key top right font ",7"
set grid
do for [s in scenes] {
  set title s
  ls = labelsOf(s)
  # Columns of bench.csv: 1 label, 12 elapsed_ms, 21 relmse.
  plot for [l in ls] frames using (strcol(1) eq l ? $12 : NaN):21 with linespoints \
       pointsize 0.5 title shortOf(l)
}
unset multiplot

set output dir."/bench_stages.png"
set terminal pngcairo size 1100,600 font ",8"
unset logscale
unset grid
set title "mean stage times per frame, both eyes, at the scored size"
set ylabel "ms per frame"
set xlabel ""
set style data histograms
set style histogram rowstacked
set style fill solid 0.8 border -1
set boxwidth 0.75
set key top left
set xtics rotate by -35 left font ",7"
set bmargin 12
set rmargin 16
# Columns: 14 gbuffer, 15 readback, 16 rebuild, 17 trace, 18 denoise (ms).
scored = "< awk -F, 'NR > 1 && $13 == 1 { $2 = $3 \"/\" $2; print }' OFS=, ".configs
plot scored using 14:xtic(2) title "G-buffer", \
     "" using 15 title "read-back", \
     "" using 16 title "hit rebuild", \
     "" using 17 title "trace", \
     "" using 18 title "denoise"
