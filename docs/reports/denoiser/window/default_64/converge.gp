set terminal pngcairo size 1100,480 font 'sans,10' noenhanced
set output '/tmp/dn/w2/.converge.png.tmp'
set logscale xy
set grid
set key bottom left
set xlabel 'time (s)'
$d0 << EOD
0.0197394 0.724475 0.593277
0.0479832 3.10647 28.0782
0.103101 1.55482 13.9153
0.183164 0.400012 6.83252
0.340052 0.110361 3.29706
0.675778 0.100069 1.54967
1.37553 0.0418101 0.691833
2.72104 19.2217 2.57466
5.44164 4.82167 1.30116
EOD
$d1 << EOD
0.022486 0.134793 0.557622
0.0522816 1.49154 27.8686
0.105619 0.373478 13.6617
0.185669 0.0936408 6.60828
0.34258 0.0251139 3.14777
0.678327 0.00900063 1.49132
1.37839 0.0054604 0.648553
2.72374 0.0816634 0.333535
5.44439 0.0261385 0.248165
EOD
set multiplot layout 1,2 title 'default_scene.gltf'
set ylabel 'relMSE'
plot $d0 using 1:2 with linespoints title 'denoised raw', $d1 using 1:2 with linespoints title 'denoised denoised'
set ylabel 'RMSE'
plot $d0 using 1:3 with linespoints title 'denoised raw', $d1 using 1:3 with linespoints title 'denoised denoised'
unset multiplot
