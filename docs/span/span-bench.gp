# frugal-lab span-bench: error of each interpolator against the exact line (LSB), by span length.
set terminal svg size 960,420 dynamic enhanced
set output 'span-bench.svg'
set datafile separator ','
set logscale x 2
set xlabel 'span length (pixels)'
set grid
set key top left
set multiplot layout 1,2
set title 'worst error'
set ylabel 'LSB'
set logscale y 2
set yrange [0.5:*]
plot 'span-bench.csv' every ::1 using 2:(($1 == 16 && strcol(3) eq 'span') ? ($4 > 0 ? $4 : 0.5) : NaN) with linespoints title 'span 16-bit', \
     'span-bench.csv' every ::1 using 2:(($1 == 16 && strcol(3) eq 'span_trunc') ? ($4 > 0 ? $4 : 0.5) : NaN) with linespoints title 'span_trunc 16-bit', \
     'span-bench.csv' every ::1 using 2:(($1 == 16 && strcol(3) eq 'dda') ? ($4 > 0 ? $4 : 0.5) : NaN) with linespoints title 'dda 16-bit', \
     'span-bench.csv' every ::1 using 2:(($1 == 16 && strcol(3) eq 'exact') ? ($4 > 0 ? $4 : 0.5) : NaN) with linespoints title 'exact 16-bit', \
     'span-bench.csv' every ::1 using 2:(($1 == 24 && strcol(3) eq 'span') ? ($4 > 0 ? $4 : 0.5) : NaN) with linespoints title 'span 24-bit', \
     'span-bench.csv' every ::1 using 2:(($1 == 24 && strcol(3) eq 'span_trunc') ? ($4 > 0 ? $4 : 0.5) : NaN) with linespoints title 'span_trunc 24-bit', \
     'span-bench.csv' every ::1 using 2:(($1 == 24 && strcol(3) eq 'dda') ? ($4 > 0 ? $4 : 0.5) : NaN) with linespoints title 'dda 24-bit', \
     'span-bench.csv' every ::1 using 2:(($1 == 24 && strcol(3) eq 'exact') ? ($4 > 0 ? $4 : 0.5) : NaN) with linespoints title 'exact 24-bit'
set title 'mean error'
set ylabel 'LSB'
unset logscale y
set yrange [0:*]
plot 'span-bench.csv' every ::1 using 2:(($1 == 16 && strcol(3) eq 'span') ? $5 : NaN) with linespoints title 'span 16-bit', \
     'span-bench.csv' every ::1 using 2:(($1 == 16 && strcol(3) eq 'span_trunc') ? $5 : NaN) with linespoints title 'span_trunc 16-bit', \
     'span-bench.csv' every ::1 using 2:(($1 == 16 && strcol(3) eq 'dda') ? $5 : NaN) with linespoints title 'dda 16-bit', \
     'span-bench.csv' every ::1 using 2:(($1 == 16 && strcol(3) eq 'exact') ? $5 : NaN) with linespoints title 'exact 16-bit', \
     'span-bench.csv' every ::1 using 2:(($1 == 24 && strcol(3) eq 'span') ? $5 : NaN) with linespoints title 'span 24-bit', \
     'span-bench.csv' every ::1 using 2:(($1 == 24 && strcol(3) eq 'span_trunc') ? $5 : NaN) with linespoints title 'span_trunc 24-bit', \
     'span-bench.csv' every ::1 using 2:(($1 == 24 && strcol(3) eq 'dda') ? $5 : NaN) with linespoints title 'dda 24-bit', \
     'span-bench.csv' every ::1 using 2:(($1 == 24 && strcol(3) eq 'exact') ? $5 : NaN) with linespoints title 'exact 24-bit'
unset multiplot
