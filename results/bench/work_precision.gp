# asperity plot script: `gnuplot work_precision.gp` redraws work_precision.png (data inline; restyle freely)
set terminal pngcairo size 1500,900 enhanced
set output 'work_precision.png'
$reference << EOD
0.5728 100 1.559e-05 8.028e-05 5.023e-05 0.0004604 0.1171 0.1405
5.614 1000 5.417e-06 7.523e-06 7.937e-06 4.686e-05 0.0005003 0.007076
55.5 10000 3.116e-07 6.726e-07 6.659e-07 4.052e-06 0.0001318 1.653e-05
165.3 30000 2.072e-08 1.974e-07 1.812e-07 1.224e-06 1.553e-05 4.396e-06
EOD
$reference_ends << EOD
0.5728 100 1.559e-05 8.028e-05 5.023e-05 0.0004604 0.1171 0.1405
165.3 30000 2.072e-08 1.974e-07 1.812e-07 1.224e-06 1.553e-05 4.396e-06
EOD
$event << EOD
0.001742 0.0001 4.343e-06 3.662e-08 3.26e-07 1.929e-07 8.171e-05 3.116e-05
0.002349 1e-05 1.301e-08 3.814e-09 8.712e-08 1.567e-08 4.07e-05 6.646e-06
0.003329 1e-06 2.407e-08 4.041e-10 1.625e-08 2.832e-09 4.998e-06 7.701e-07
0.004794 1e-07 5.034e-09 3.473e-11 2.214e-09 2.099e-10 8.125e-07 1.051e-07
0.007161 1e-08 7.67e-10 3.748e-12 3.005e-10 2.372e-11 9.82e-08 1.238e-08
0.01045 1e-09 8.437e-11 3.331e-13 3.118e-11 1.65e-12 1.596e-08 1.74e-09
0.01578 1e-10 1.023e-11 2.945e-14 3.52e-12 1.13e-13 1.487e-09 1.6e-10
0.02425 1e-11 1.04e-12 2.594e-15 3.482e-13 1.024e-14 5.446e-11 1.005e-11
0.05708 1e-13 1.072e-13 3.052e-16 3.651e-14 1.444e-15 1.684e-11 2.032e-12
EOD
$event_ends << EOD
0.001742 0.0001 4.343e-06 3.662e-08 3.26e-07 1.929e-07 8.171e-05 3.116e-05
0.05708 1e-13 1.072e-13 3.052e-16 3.651e-14 1.444e-15 1.684e-11 2.032e-12
EOD
set label 99 'STAND-IN data' at screen 0.995, 0.012 right front textcolor rgb '#b2182b' font ',8'
set multiplot layout 2,3 scale 1, 0.95 offset 0, 0.012 title 'Work-precision on bench experiment P0.20N (60 junctions): error vs converged event run (tol 1e-12)'
set logscale xy
set offsets 0, 0, graph 0.05, graph 0.05
set format y '10^{%T}'
set format x '10^{%T}'
set grid
set xlabel 'wall time [s]'
set ylabel 'relative error [1]'
set key bmargin center horizontal font ',9'
set title 'Q_s'
plot $reference using 1:3 with linespoints pt 7 ps 0.6 lw 1.5 title 'reference, C_t 100 … 30000', $reference_ends using 1:3:(sprintf('%g',$2)) with labels right offset -1,0 font ',8' notitle, $event using 1:3 with linespoints pt 5 ps 0.6 lw 1.5 title 'event, tol 0.0001 … 1e-13', $event_ends using 1:3:(sprintf('%g',$2)) with labels left offset 1,0 font ',8' notitle
set title 'A_s'
plot $reference using 1:4 with linespoints pt 7 ps 0.6 lw 1.5 title 'reference, C_t 100 … 30000', $reference_ends using 1:4:(sprintf('%g',$2)) with labels right offset -1,0 font ',8' notitle, $event using 1:4 with linespoints pt 5 ps 0.6 lw 1.5 title 'event, tol 0.0001 … 1e-13', $event_ends using 1:4:(sprintf('%g',$2)) with labels left offset 1,0 font ',8' notitle
set title 't_{peak}'
plot $reference using 1:5 with linespoints pt 7 ps 0.6 lw 1.5 title 'reference, C_t 100 … 30000', $reference_ends using 1:5:(sprintf('%g',$2)) with labels right offset -1,0 font ',8' notitle, $event using 1:5 with linespoints pt 5 ps 0.6 lw 1.5 title 'event, tol 0.0001 … 1e-13', $event_ends using 1:5:(sprintf('%g',$2)) with labels left offset 1,0 font ',8' notitle
set title 'α'
plot $reference using 1:6 with linespoints pt 7 ps 0.6 lw 1.5 title 'reference, C_t 100 … 30000', $reference_ends using 1:6:(sprintf('%g',$2)) with labels right offset -1,0 font ',8' notitle, $event using 1:6 with linespoints pt 5 ps 0.6 lw 1.5 title 'event, tol 0.0001 … 1e-13', $event_ends using 1:6:(sprintf('%g',$2)) with labels left offset 1,0 font ',8' notitle
set title 'stick-slip drop ΔQ_{ss}'
plot $reference using 1:7 with linespoints pt 7 ps 0.6 lw 1.5 title 'reference, C_t 100 … 30000', $reference_ends using 1:7:(sprintf('%g',$2)) with labels right offset -1,0 font ',8' notitle, $event using 1:7 with linespoints pt 5 ps 0.6 lw 1.5 title 'event, tol 0.0001 … 1e-13', $event_ends using 1:7:(sprintf('%g',$2)) with labels left offset 1,0 font ',8' notitle
set title 'stick-slip period T_{ss}'
plot $reference using 1:8 with linespoints pt 7 ps 0.6 lw 1.5 title 'reference, C_t 100 … 30000', $reference_ends using 1:8:(sprintf('%g',$2)) with labels right offset -1,0 font ',8' notitle, $event using 1:8 with linespoints pt 5 ps 0.6 lw 1.5 title 'event, tol 0.0001 … 1e-13', $event_ends using 1:8:(sprintf('%g',$2)) with labels left offset 1,0 font ',8' notitle
unset multiplot

unset output
