# frugal-lab write-bench: PNG size against encoding time per plane (drawn from the CSV)
set terminal svg size 1200,420 dynamic
set output '/work/main/docs/writing/write-bench.svg'
set datafile separator ','
set key top right
set grid
set multiplot layout 1,3
set title 'color'
set xlabel 'encode ms (fastest of the repeats)'
set ylabel 'bytes / baseline'
set yrange [0:*]
plot '/work/main/docs/writing/write-bench.csv' every ::1 using (strcol(2) eq 'color' && strcol(3) ne 'baseline' && strcol(5) eq 'none' ? $11 : NaN):8 with points title 'none', '/work/main/docs/writing/write-bench.csv' every ::1 using (strcol(2) eq 'color' && strcol(3) ne 'baseline' && strcol(5) eq 'sub' ? $11 : NaN):8 with points title 'sub', '/work/main/docs/writing/write-bench.csv' every ::1 using (strcol(2) eq 'color' && strcol(3) ne 'baseline' && strcol(5) eq 'up' ? $11 : NaN):8 with points title 'up', '/work/main/docs/writing/write-bench.csv' every ::1 using (strcol(2) eq 'color' && strcol(3) ne 'baseline' && strcol(5) eq 'paeth' ? $11 : NaN):8 with points title 'paeth', '/work/main/docs/writing/write-bench.csv' every ::1 using (strcol(2) eq 'color' && strcol(3) eq 'baseline' ? $11 : NaN):8 with points pt 7 ps 1.5 title 'baseline (zlib 6)', 1.1 with lines dt 2 title 'size limit'
set title 'depth'
set xlabel 'encode ms (fastest of the repeats)'
set ylabel 'bytes / baseline'
set yrange [0:*]
plot '/work/main/docs/writing/write-bench.csv' every ::1 using (strcol(2) eq 'depth' && strcol(3) ne 'baseline' && strcol(5) eq 'none' ? $11 : NaN):8 with points title 'none', '/work/main/docs/writing/write-bench.csv' every ::1 using (strcol(2) eq 'depth' && strcol(3) ne 'baseline' && strcol(5) eq 'sub' ? $11 : NaN):8 with points title 'sub', '/work/main/docs/writing/write-bench.csv' every ::1 using (strcol(2) eq 'depth' && strcol(3) ne 'baseline' && strcol(5) eq 'up' ? $11 : NaN):8 with points title 'up', '/work/main/docs/writing/write-bench.csv' every ::1 using (strcol(2) eq 'depth' && strcol(3) ne 'baseline' && strcol(5) eq 'paeth' ? $11 : NaN):8 with points title 'paeth', '/work/main/docs/writing/write-bench.csv' every ::1 using (strcol(2) eq 'depth' && strcol(3) eq 'baseline' ? $11 : NaN):8 with points pt 7 ps 1.5 title 'baseline (zlib 6)', 1.1 with lines dt 2 title 'size limit'
set title 'ids'
set xlabel 'encode ms (fastest of the repeats)'
set ylabel 'bytes / baseline'
set yrange [0:*]
plot '/work/main/docs/writing/write-bench.csv' every ::1 using (strcol(2) eq 'ids' && strcol(3) ne 'baseline' && strcol(5) eq 'none' ? $11 : NaN):8 with points title 'none', '/work/main/docs/writing/write-bench.csv' every ::1 using (strcol(2) eq 'ids' && strcol(3) ne 'baseline' && strcol(5) eq 'sub' ? $11 : NaN):8 with points title 'sub', '/work/main/docs/writing/write-bench.csv' every ::1 using (strcol(2) eq 'ids' && strcol(3) ne 'baseline' && strcol(5) eq 'up' ? $11 : NaN):8 with points title 'up', '/work/main/docs/writing/write-bench.csv' every ::1 using (strcol(2) eq 'ids' && strcol(3) ne 'baseline' && strcol(5) eq 'paeth' ? $11 : NaN):8 with points title 'paeth', '/work/main/docs/writing/write-bench.csv' every ::1 using (strcol(2) eq 'ids' && strcol(3) eq 'baseline' ? $11 : NaN):8 with points pt 7 ps 1.5 title 'baseline (zlib 6)', 1.1 with lines dt 2 title 'size limit'
unset multiplot
