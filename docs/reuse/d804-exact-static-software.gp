# frugal-lab reuse-bench: the CSV's two plots (gnuplot 5, svg terminal)
set terminal svg size 1000,800 dynamic enhanced font 'sans,10'
set output 'd804-exact-static-software.svg'
set datafile separator ','
modes = "reuse rebuild full"
is(k) = strcol(2) eq word(modes, k)
$paper << EOD
55.44,1.8588,804 polygons
98.66,8.3158,1404 polygons
EOD
set key outside right top noenhanced
set multiplot layout 2,1
set title 'speed-up (full ÷ reuse) against the static share, one point per frame' noenhanced
set xlabel 'static triangles (%)' noenhanced
set ylabel 'speed-up' noenhanced
set xrange [0:100]
set yrange [0:*]
plot for [k=1:3] 'd804-exact-static-software.csv' skip 1 using (is(k) ? 100 * $11 : NaN):(is(k) ? $10 : NaN) with points lt k pt 7 title word(modes, k), $paper using 1:2 with points pt 5 ps 1.5 lc 'black' title 'paper 000', $paper using 1:2:3 with labels offset char -1,1 right notitle, 1 with lines dt 2 lc 'black' title 'speed-up 1', '+' using (50):(1) with points lc rgb '#FF000000' notitle
set title 'time per frame (medians of the rounds)' noenhanced
set xlabel 'frame' noenhanced
set ylabel 'ms' noenhanced
set autoscale x
set yrange [0:*]
plot 'd804-exact-static-software.csv' skip 1 using 1:3 with linespoints pt 7 ps 0.5 title 'full', 'd804-exact-static-software.csv' skip 1 using 1:4 with linespoints pt 7 ps 0.5 title 'reuse', 'd804-exact-static-software.csv' skip 1 using 1:6 with linespoints pt 7 ps 0.5 title 'oracle (cells)', 'd804-exact-static-software.csv' skip 1 using 1:7 with linespoints pt 7 ps 0.5 title 'oracle (whole)', 'd804-exact-static-software.csv' skip 1 using 1:8 with lines dt 2 title 'model', '+' using (70):(1) with points lc rgb '#FF000000' notitle
unset multiplot
