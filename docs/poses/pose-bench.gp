# frugal-lab pose-bench: the deforming scene's frame time beside its rest pose's.
# Drawn from the CSV; run gnuplot on this file to draw it again.
set terminal svg size 560,400 dynamic background rgb 'white'
set output 'pose-bench.svg'
set datafile separator ','
set title 'poses: tube' noenhanced
set ylabel 'frame time (ms, median; bars: min to max)'
set yrange [0:*]
set style fill solid 0.6 border -1
set boxwidth 0.6
set grid ytics
plot 'pose-bench.csv' skip 1 using 0:2:xtic(1) with boxes notitle, \
     '' skip 1 using 0:2:3:4 with yerrorbars notitle lc rgb 'black'
