# frugal cull-report: the CSV's two plots (gnuplot 5, svg terminal)
set terminal svg size 1000,700 dynamic enhanced font 'sans,10'
set output 'docs/occlusion/three-bunnies.svg'
set datafile separator ','
methods = "none sphere backface cones paper conservative oracle"
n = words(methods)
is(k) = strcol(3) eq word(methods, k)
set key outside right top noenhanced
set multiplot layout 2,1
set title 'cull + draw time against misses (one point per view)' noenhanced
set xlabel 'misses (visible triangles not drawn)' noenhanced
set ylabel 'cull + draw (ms)' noenhanced
set offsets graph 0.03, graph 0.03, graph 0.05, 0
plot for [k=1:n] 'docs/occlusion/three-bunnies.csv' skip 1 using (is(k) ? $7 : NaN):(is(k) ? $10 + $11 : NaN) with points lt k pt 7 title word(methods, k), '+' using (0):(0) with points lc rgb '#FF000000' notitle
set title '(cull + draw) / oracle draw, per view' noenhanced
set xlabel 'view' noenhanced
set ylabel 'ratio to oracle' noenhanced
set autoscale xfix
set offsets 0.5, 0.5, graph 0.05, 0
set xtics 1
set style fill solid 0.8 border -1
w = 0.8 / n
set boxwidth w absolute
plot for [k=1:n] 'docs/occlusion/three-bunnies.csv' skip 1 using (is(k) ? $1 + (k - (n + 1) / 2.0) * w : NaN):(is(k) ? $12 : NaN) with boxes lt k title word(methods, k), 1 with lines dt 2 lc 'black' title 'ratio 1', '+' using (0):(0) with points lc rgb '#FF000000' notitle
unset multiplot
