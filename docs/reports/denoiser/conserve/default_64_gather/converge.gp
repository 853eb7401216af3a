set terminal pngcairo size 1100,480 font 'sans,10' noenhanced
set output '/tmp/dn/c0/.converge.png.tmp'
set logscale xy
set grid
set key bottom left
set xlabel 'time (s)'
$d0 << EOD
0.02268 0.724475 0.593277
0.0457204 3.10647 28.0782
0.0936667 1.55482 13.9153
0.191379 0.400012 6.83252
0.390972 0.110361 3.29706
0.799366 0.100069 1.54967
1.46698 0.0418101 0.691833
2.97023 19.2217 2.57466
6.32505 4.82167 1.30116
EOD
$d1 << EOD
0.0256444 0.130009 0.542591
0.0484142 1.30537 26.1234
0.0969792 0.321152 12.6641
0.193875 0.0841607 6.26648
0.393407 0.0230818 3.01436
0.801591 0.00807066 1.39201
1.46921 0.00521661 0.620384
2.97388 0.0186751 0.314541
6.32719 0.0141965 0.251532
EOD
set multiplot layout 1,2 title 'default_scene.gltf'
set ylabel 'relMSE'
plot $d0 using 1:2 with linespoints title 'denoised raw', $d1 using 1:2 with linespoints title 'denoised denoised'
set ylabel 'RMSE'
plot $d0 using 1:3 with linespoints title 'denoised raw', $d1 using 1:3 with linespoints title 'denoised denoised'
unset multiplot
