# asperity plot script: `gnuplot work_precision.gp` redraws work_precision.png (data inline; restyle freely)
set terminal pngcairo size 1500,900 enhanced
set output 'work_precision.png'
$reference << EOD
0.572793 100 1.55933e-05 8.02784e-05 5.02309e-05 0.000460409 0.11708 0.140515
5.61448 1000 5.41699e-06 7.52338e-06 7.93691e-06 4.68607e-05 0.000500324 0.00707596
55.5027 10000 3.11639e-07 6.72597e-07 6.6593e-07 4.05236e-06 0.000131798 1.65325e-05
165.292 30000 2.07194e-08 1.97421e-07 1.81198e-07 1.22387e-06 1.55319e-05 4.39609e-06
EOD
$reference_ends << EOD
0.572793 100 1.55933e-05 8.02784e-05 5.02309e-05 0.000460409 0.11708 0.140515
165.292 30000 2.07194e-08 1.97421e-07 1.81198e-07 1.22387e-06 1.55319e-05 4.39609e-06
EOD
$event << EOD
0.00174226 0.0001 4.34308e-06 3.66193e-08 3.25969e-07 1.92864e-07 8.17129e-05 3.11605e-05
0.00234949 1e-05 1.30136e-08 3.81351e-09 8.71186e-08 1.56717e-08 4.07024e-05 6.64606e-06
0.00332921 1e-06 2.4073e-08 4.0414e-10 1.62471e-08 2.83239e-09 4.99755e-06 7.70054e-07
0.00479417 1e-07 5.03437e-09 3.47287e-11 2.21352e-09 2.09935e-10 8.12483e-07 1.05073e-07
0.00716089 1e-08 7.66979e-10 3.7485e-12 3.00542e-10 2.37244e-11 9.82027e-08 1.23812e-08
0.0104547 1e-09 8.43721e-11 3.33101e-13 3.11777e-11 1.65044e-12 1.59633e-08 1.74039e-09
0.0157778 1e-10 1.0232e-11 2.94496e-14 3.52036e-12 1.13049e-13 1.48692e-09 1.59955e-10
0.0242495 1e-11 1.03981e-12 2.59401e-15 3.48162e-13 1.02414e-14 5.44563e-11 1.00502e-11
0.0570814 1e-13 1.07159e-13 3.05177e-16 3.65133e-14 1.4443e-15 1.68437e-11 2.03172e-12
EOD
$event_ends << EOD
0.00174226 0.0001 4.34308e-06 3.66193e-08 3.25969e-07 1.92864e-07 8.17129e-05 3.11605e-05
0.0570814 1e-13 1.07159e-13 3.05177e-16 3.65133e-14 1.4443e-15 1.68437e-11 2.03172e-12
EOD
set multiplot layout 2,3 title 'Work-precision on bench experiment P0.20N (60 junctions, stand-in recipe): error vs converged event run (tol 1e-12)'
set logscale xy
set format y '10^{%T}'
set format x '10^{%T}'
set grid
set xlabel 'wall time [s]'
set ylabel 'relative error'
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
