# asperity plot script: `gnuplot savings.gp` redraws savings.png (data inline; restyle freely)
set terminal pngcairo size 1200,600 enhanced
set output 'savings.png'
$d << EOD
"series\noutput.series=[]\nvs all series columns" 137.27 129.22
"stop\nstop.at_first_peak=true\nvs peak + 5 cycles" 127.28 121.28
"area_law\nalpha_b=0 (linear)\nvs alpha_b=7.25e-16" 129.79 16.935
EOD
set label 99 'STAND-IN data' at screen 0.995, 0.012 right front textcolor rgb '#b2182b' font ',8'
set title 'Model only what a scene requires: P4.00N' . "\n" . 'CPU time of integration + writing the run directory'
set style data histograms
set style histogram clustered gap 1
set style fill solid 0.8 border -1
set xtics noenhanced
set bmargin 5
set boxwidth 0.9
set ylabel 'CPU time [ms]'
set grid ytics
set yrange [0:*]
set key top right
stats $d using ($2 > $3 ? $2 : $3) nooutput
step = STATS_max > 0 ? 10**floor(log10(STATS_max / 5.0)) : 1
m = STATS_max > 0 ? STATS_max / (5.0 * step) : 1
tic = (m <= 1 ? 1 : (m <= 2 ? 2 : (m <= 5 ? 5 : 10))) * step
set ytics tic
plot $d using 2:xticlabels(1) title 'baseline' lc rgb '#4477aa', '' using 3 title 'variant (saving)' lc rgb '#ee6677'

unset output
