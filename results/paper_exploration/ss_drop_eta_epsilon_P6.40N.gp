# asperity plot script: `gnuplot ss_drop_eta_epsilon_P6.40N.gp` redraws ss_drop_eta_epsilon_P6.40N.png (data inline; restyle freely)
set terminal pngcairo size 900,700 enhanced
set output 'ss_drop_eta_epsilon_P6.40N.png'
set label 99 'STAND-IN data' at screen 0.995, 0.012 right front textcolor rgb '#b2182b' font ',8'
set title 'stick-slip drop ΔQ_{ss} over η × ε, P6.40N' . "\n" . '(blank: no value (NaN), or a failed point)'
set rmargin at screen 0.74
if (GPVAL_TERM eq 'svg') { set label 98 'stick-slip drop ΔQ_{ss} [N]' at screen 0.975, graph 0.5 center rotate by 90 } else { set cblabel 'stick-slip drop ΔQ_{ss} [N]' }
set palette defined (0 '#440154', 1 '#3b528b', 2 '#21908d', 3 '#5dc963', 4 '#fde725')
$cells << EOD
0 0.5 -25 25 0.45 0.55 0.8868706610843227
0 0.6 -25 25 0.55 0.6499999999999999 0.6138875661177394
0 0.7 -25 25 0.6499999999999999 0.75 1.8349034439989447
0 0.8 -25 25 0.75 0.8500000000000001 1.26122630085872
0 0.9 -25 25 0.8500000000000001 0.925 0.5852139771185401
0 0.95 -25 25 0.925 0.97 0.29139485293420364
50 0.5 25 75 0.45 0.55 3.178417274526035
50 0.6 25 75 0.55 0.6499999999999999 2.1545505649332273
50 0.7 25 75 0.6499999999999999 0.75 1.3315199578797179
50 0.8 25 75 0.75 0.8500000000000001 0.8707439915808021
50 0.9 25 75 0.8500000000000001 0.925 0.3808136997343802
50 0.95 25 75 0.925 0.97 0.15826928298521992
100 0.5 75 125 0.45 0.55 2.221292196629919
100 0.6 75 125 0.55 0.6499999999999999 2.16874122601242
100 0.7 75 125 0.6499999999999999 0.75 1.1010259399233209
100 0.8 75 125 0.75 0.8500000000000001 0.7414886025205595
100 0.9 75 125 0.8500000000000001 0.925 0.2705006750105907
150 0.5 125 165 0.45 0.55 2.300336625889217
150 0.6 125 165 0.55 0.6499999999999999 1.726504778083712
150 0.7 125 165 0.6499999999999999 0.75 1.1521364194165378
150 0.8 125 165 0.75 0.8500000000000001 0.6235830637366904
180 0.5 165 190 0.45 0.55 2.018968197025404
180 0.6 165 190 0.55 0.6499999999999999 1.4767876349639306
180 0.7 165 190 0.6499999999999999 0.75 1.1983933516879433
EOD
stats $cells using 7 nooutput
step = (STATS_max - STATS_min) > 0 ? 10**floor(log10((STATS_max - STATS_min) / 5.0)) : 1
m = (STATS_max - STATS_min) > 0 ? (STATS_max - STATS_min) / (5.0 * step) : 1
tic = (m <= 1 ? 1 : (m <= 2 ? 2 : (m <= 5 ? 5 : 10))) * step
set cbtics tic
if (STATS_max == STATS_min) { set cbtics (STATS_min) }
set xlabel 'η [s^{-1}]'
set xtics ('0' 0, '50' 50, '100' 100, '150' 150, '' 180, '200' 200, '250' 250)
set xrange [-25:275]
set ylabel 'ε [1]'
set ytics ('0.5' 0.5, '0.6' 0.6, '0.7' 0.7, '0.8' 0.8, '0.9' 0.9, '' 0.95, '0.99' 0.99)
set yrange [0.45:1.01]
plot $cells using 1:2:3:4:5:6:7 with boxxyerror fs solid 1.0 noborder lc palette notitle

unset output
