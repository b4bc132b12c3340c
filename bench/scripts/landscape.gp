# The objective's landscape (scripts/landscape.sh): reads landscape.csv, writes landscape.png in
# the current folder.
set datafile separator ","
set terminal pngcairo size 1500,450 font ",11"
set output "landscape.png"
set multiplot layout 1,3 title "Joint objective J through the truth of a SYNTHETIC experiment (P0.98N junctions, 0.2 % noise, Q(t) to 2.3 t_{peak})"
set logscale y
set format y "10^{%L}"
set xlabel "parameter / truth"
set ylabel "J (chi-square)"
set key top center
set grid
do for [p in "model.alpha_b model.epsilon model.eta"] {
  set title p noenhanced
  plot "landscape.csv" using ((strcol(1) eq p) ? $2 : 1/0):4 with linespoints pt 7 ps 0.5 title "pointwise", \
       "" using ((strcol(1) eq p) ? $2 : 1/0):5 with linespoints pt 7 ps 0.5 title "cycles: mean drop and period", \
       "" using ((strcol(1) eq p) ? $2 : 1/0):6 with linespoints pt 7 ps 0.5 title "peaks paired by time"
}
unset multiplot
