# frugal-lab hsr-bench: speed-up over the z-buffer per mode, measured and the paper's (Table 1).
# Drawn from the CSV; run gnuplot on this file to draw it again.
set terminal svg size 720,420 dynamic background rgb 'white'
set output 'cubes-software.svg'
set datafile separator ','
set title 'hidden-surface modes: builtin:cubes, 240x320, software' noenhanced
set ylabel 'frames per second / z-buffer'
set style data histograms
set style histogram clustered gap 1
set style fill solid 0.8 border -1
set boxwidth 0.9
set yrange [0:*]
set grid ytics
set key top left
plot 'cubes-software.csv' using 11:xtic(5) title 'measured', '' using 13 title 'paper (IPAQ 3660)'
