set terminal pngcairo size 1100,480 font 'sans,10' noenhanced
set output '/tmp/dn/c1b/.converge.png.tmp'
set logscale xy
set grid
set key bottom left
set xlabel 'time (s)'
$d0 << EOD
0.0209255 0.724475 0.593277
0.0413136 3.10647 28.0782
0.0862978 1.55482 13.9153
0.179274 0.400012 6.83252
0.359867 0.110361 3.29706
0.708518 0.100069 1.54967
1.48633 0.0418101 0.691833
2.8995 19.2217 2.57466
5.74196 4.82167 1.30116
EOD
$d1 << EOD
0.0233839 0.140664 0.5302
0.0439876 3.01979 27.0483
0.0899191 1.16545 13.2696
0.182189 0.322601 6.51969
0.363148 0.0980042 3.13339
0.711582 0.0330547 1.45758
1.48898 0.0171744 0.647586
2.90367 1.13281 0.707695
5.74449 0.303738 0.407645
EOD
set multiplot layout 1,2 title 'default_scene.gltf'
set ylabel 'relMSE'
plot $d0 using 1:2 with linespoints title 'denoised raw', $d1 using 1:2 with linespoints title 'denoised denoised'
set ylabel 'RMSE'
plot $d0 using 1:3 with linespoints title 'denoised raw', $d1 using 1:3 with linespoints title 'denoised denoised'
unset multiplot
