# asperity plot script: `gnuplot savings.gp` redraws savings.png (data inline; restyle freely)
set terminal pngcairo size 1000,600 enhanced
set output 'savings.png'
$d << EOD
"series\noutput.series=[]\nvs all series columns" 137.31 129.27
"stop\nstop.at_first_peak=true\nvs peak + 5 cycles" 127.25 121.29
"area_law\nalpha_b=0 (linear)\nvs alpha_b=7.25e-16" 129.81 16.935
EOD
set title 'Model only what a scene requires: P4.00N (stand-in)' . "\n" . 'CPU time of integration + writing the run directory'
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
plot $d using 2:xticlabels(1) title 'baseline' lc rgb '#4477aa', '' using 3 title 'variant (saving)' lc rgb '#ee6677'

unset output
