# frugal-lab soak: resident memory (VmRSS) over frames and over create/destroy cycles, from the CSV.
# Run gnuplot on this file to draw it again.
set terminal pngcairo size 1000,420 font 'sans,10'
set output 'minimal.png'
set datafile separator ','
set ylabel 'resident memory (MiB)'
set yrange [0:*]
set grid
set key bottom right noenhanced
row(run, backend) = strcol(1) eq run && strcol(2) eq backend
set title 'frames: builtin:cubes, 64x48, growth after warm-up in the key' noenhanced
set xlabel 'frames rendered'
set arrow 1 from 1000, graph 0 to 1000, graph 1 nohead dashtype 2
plot 'minimal.csv' skip 1 using (row('frames', 'egl-device (minimal)') ? $3 : NaN):($4/1024) with linespoints pointsize 0.3 title 'egl-device (minimal) (+1.24 %)', \
     'minimal.csv' skip 1 using (row('frames', 'egl-surfaceless (minimal)') ? $3 : NaN):($4/1024) with linespoints pointsize 0.3 title 'egl-surfaceless (minimal) (+0.00 %)', \
     'minimal.csv' skip 1 using (row('frames', 'osmesa (minimal)') ? $3 : NaN):($4/1024) with linespoints pointsize 0.3 title 'osmesa (minimal) (+0.00 %)'
unset arrow 1
