# asperity plot script: `gnuplot ss_drop_c_min_eta_P4.00N.gp` redraws ss_drop_c_min_eta_P4.00N.png (data inline; restyle freely)
set terminal pngcairo size 900,700 enhanced
set output 'ss_drop_c_min_eta_P4.00N.png'
set label 99 'STAND-IN data' at screen 0.995, 0.012 right front textcolor rgb '#b2182b' font ',8'
set title 'stick-slip drop ΔQ_{ss} over c_{min} × η, P4.00N' . "\n" . '(blank: no value (NaN), or a failed point)'
set rmargin at screen 0.74
if (GPVAL_TERM eq 'svg') { set label 98 'stick-slip drop ΔQ_{ss} [N]' at screen 0.975, graph 0.5 center rotate by 90 } else { set cblabel 'stick-slip drop ΔQ_{ss} [N]' }
set palette defined (0 '#440154', 1 '#3b528b', 2 '#21908d', 3 '#5dc963', 4 '#fde725')
$cells << EOD
1e-05 0 3.162277660168379e-07 0.00031622776601683794 -25 25 0.3714675104413341
1e-05 50 3.162277660168379e-07 0.00031622776601683794 25 75 0.24997200228957794
1e-05 100 3.162277660168379e-07 0.00031622776601683794 75 125 0.20878356189329655
1e-05 150 3.162277660168379e-07 0.00031622776601683794 125 165 0.18220312517597853
0.01 0 0.00031622776601683794 0.31622776601683794 -25 25 0.40933541142388963
0.01 50 0.00031622776601683794 0.31622776601683794 25 75 0.24997200230657796
0.01 100 0.00031622776601683794 0.31622776601683794 75 125 0.20878356189324557
0.01 150 0.00031622776601683794 0.31622776601683794 125 165 0.18220312517597942
EOD
stats $cells using 7 nooutput
step = (STATS_max - STATS_min) > 0 ? 10**floor(log10((STATS_max - STATS_min) / 5.0)) : 1
m = (STATS_max - STATS_min) > 0 ? (STATS_max - STATS_min) / (5.0 * step) : 1
tic = (m <= 1 ? 1 : (m <= 2 ? 2 : (m <= 5 ? 5 : 10))) * step
set cbtics tic
if (STATS_max == STATS_min) { set cbtics (STATS_min) }
set xlabel 'c_{min} [1]'
set logscale x
set xtics ('1e-05' 1e-05, '0.01' 0.01)
set xrange [3.162277660168379e-07:0.31622776601683794]
set ylabel 'η [s^{-1}]'
set ytics ('0' 0, '50' 50, '100' 100, '150' 150, '' 180, '200' 200, '250' 250)
set yrange [-25:275]
plot $cells using 1:2:3:4:5:6:7 with boxxyerror fs solid 1.0 noborder lc palette notitle

unset output
