# frugal-lab order-bench: frame time and draws per backend and draw order.
# Drawn from the CSV; run gnuplot 'materials.csv' skip 1 using 0:3:xtic(sprintf('%s %s', strcol(1), strcol(2))) with boxes title 'frame ms', '' skip 1 using 0:3:4:5 with yerrorbars lc rgb 'black' pt 0 notitle, '' skip 1 using 0:7 axes x1y2 with points pt 7 ps 1.2 title 'draws'
set terminal svg size 760,440 dynamic background rgb 'white'
set output 'materials.svg'
set datafile separator ','
set title 'draw orders: builtin:materials' noenhanced
set ylabel 'frame ms (median; bar: min to max)'
set y2label 'draws issued'
set ytics nomirror
set y2tics
set yrange [0:*]
set y2range [0:*]
set style fill solid 0.6 border -1
set boxwidth 0.7
set xtics rotate by -35 noenhanced
set grid ytics
set key top center
plot 'materials.csv' skip 1 using 0:3:xtic(sprintf('%s %s', strcol(1), strcol(2))) with boxes title 'frame ms', '' skip 1 using 0:3:4:5 with yerrorbars lc rgb 'black' pt 0 notitle, '' skip 1 using 0:7 axes x1y2 with points pt 7 ps 1.2 title 'draws'
