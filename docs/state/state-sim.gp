# frugal-lab state-sim: total state-change cost per order (set-not-held), with paper 004's columns.
set terminal svg size 1100,440 dynamic enhanced
set output 'state-sim.svg'
set datafile separator ','
set grid
set key top left
set ylabel 'total change cost'
set yrange [0:*]
set multiplot layout 1,2
set title 'Table 6: 5 states'
set xlabel 'RSSs'
plot 'state-sim.csv' every ::1 using 3:((strcol(1) eq 'set-not-held' && strcol(2) eq 'table6' && strcol(5) eq 'submit') ? $6 : NaN) with linespoints title 'submit', \
     'state-sim.csv' every ::1 using 3:((strcol(1) eq 'set-not-held' && strcol(2) eq 'table6' && strcol(5) eq 'paper') ? $6 : NaN) with linespoints title 'paper', \
     'state-sim.csv' every ::1 using 3:((strcol(1) eq 'set-not-held' && strcol(2) eq 'table6' && strcol(5) eq 'key') ? $6 : NaN) with linespoints title 'key', \
     'state-sim.csv' every ::1 using 3:((strcol(1) eq 'set-not-held' && strcol(2) eq 'table6' && strcol(5) eq 'greedy') ? $6 : NaN) with linespoints title 'greedy', \
     'state-sim.csv' every ::1 using 3:((strcol(1) eq 'set-not-held' && strcol(2) eq 'table6' && strcol(5) eq 'lookahead') ? $6 : NaN) with linespoints title 'lookahead', \
     'state-sim.csv' every ::1 using 3:((strcol(1) eq 'set-not-held' && strcol(2) eq 'table6' && strcol(5) eq 'best') ? $6 : NaN) with linespoints title 'best', \
     'state-sim.csv' every ::1 using 3:((strcol(1) eq 'set-not-held' && strcol(2) eq 'table6' && strcol(5) eq 'submit') ? $9 : NaN) with points pt 6 ps 1.5 title 'paper: not-sorted', \
     'state-sim.csv' every ::1 using 3:((strcol(1) eq 'set-not-held' && strcol(2) eq 'table6' && strcol(5) eq 'submit') ? $8 : NaN) with points pt 4 ps 1.5 title 'paper: sorted'
set title 'Table 7: 50 RSSs'
set xlabel 'states'
plot 'state-sim.csv' every ::1 using 4:((strcol(1) eq 'set-not-held' && strcol(2) eq 'table7' && strcol(5) eq 'submit') ? $6 : NaN) with linespoints title 'submit', \
     'state-sim.csv' every ::1 using 4:((strcol(1) eq 'set-not-held' && strcol(2) eq 'table7' && strcol(5) eq 'paper') ? $6 : NaN) with linespoints title 'paper', \
     'state-sim.csv' every ::1 using 4:((strcol(1) eq 'set-not-held' && strcol(2) eq 'table7' && strcol(5) eq 'key') ? $6 : NaN) with linespoints title 'key', \
     'state-sim.csv' every ::1 using 4:((strcol(1) eq 'set-not-held' && strcol(2) eq 'table7' && strcol(5) eq 'greedy') ? $6 : NaN) with linespoints title 'greedy', \
     'state-sim.csv' every ::1 using 4:((strcol(1) eq 'set-not-held' && strcol(2) eq 'table7' && strcol(5) eq 'lookahead') ? $6 : NaN) with linespoints title 'lookahead', \
     'state-sim.csv' every ::1 using 4:((strcol(1) eq 'set-not-held' && strcol(2) eq 'table7' && strcol(5) eq 'best') ? $6 : NaN) with linespoints title 'best', \
     'state-sim.csv' every ::1 using 4:((strcol(1) eq 'set-not-held' && strcol(2) eq 'table7' && strcol(5) eq 'submit') ? $9 : NaN) with points pt 6 ps 1.5 title 'paper: not-sorted', \
     'state-sim.csv' every ::1 using 4:((strcol(1) eq 'set-not-held' && strcol(2) eq 'table7' && strcol(5) eq 'submit') ? $8 : NaN) with points pt 4 ps 1.5 title 'paper: sorted'
unset multiplot
