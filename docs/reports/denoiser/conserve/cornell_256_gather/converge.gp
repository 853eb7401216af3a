set terminal pngcairo size 1100,480 font 'sans,10' noenhanced
set output '/tmp/dn/cornell_c0/.converge.png.tmp'
set logscale xy
set grid
set key bottom left
set xlabel 'time (s)'
$d0 << EOD
0.27238 0.519738 0.269335
0.570875 0.216966 0.16441
1.18635 0.0926877 0.100809
2.38848 0.0403562 0.0621712
4.38241 0.0204881 0.044769
4.63643 0.0182123 0.040818
9.38688 0.0082616 0.0269342
9.66854 0.0082154 0.027356
17.085 0.00417483 0.0192037
EOD
$d1 << EOD
0.334739 0.0821387 0.151221
0.637324 0.0192804 0.114449
1.24099 0.00852893 0.112882
2.45265 0.00333904 0.0418532
4.43658 0.00255292 0.0329945
4.69498 0.00203904 0.0321916
9.4597 0.00142721 0.0268549
9.72891 0.00166469 0.0262246
17.1327 0.00105093 0.0192189
EOD
set multiplot layout 1,2 title 'cornell.gltf'
set ylabel 'relMSE'
plot $d0 using 1:2 with linespoints title 'denoised raw', $d1 using 1:2 with linespoints title 'denoised denoised'
set ylabel 'RMSE'
plot $d0 using 1:3 with linespoints title 'denoised raw', $d1 using 1:3 with linespoints title 'denoised denoised'
unset multiplot
