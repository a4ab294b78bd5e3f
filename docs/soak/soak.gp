# frugal-lab soak: resident memory (VmRSS) over frames and over create/destroy cycles, from the CSV.
# Run gnuplot on this file to draw it again.
set terminal pngcairo size 1000,800 font 'sans,10'
set output 'soak.png'
set datafile separator ','
set ylabel 'resident memory (MiB)'
set yrange [0:*]
set grid
set key bottom right noenhanced
set multiplot layout 2,1
row(run, backend) = strcol(1) eq run && strcol(2) eq backend
set title 'frames: builtin:cubes, 64x48, growth after warm-up in the key' noenhanced
set xlabel 'frames rendered'
set arrow 1 from 1000, graph 0 to 1000, graph 1 nohead dashtype 2
plot 'soak.csv' skip 1 using (row('frames', 'software') ? $3 : NaN):($4/1024) with linespoints pointsize 0.3 title 'software (+0.00 %)', \
     'soak.csv' skip 1 using (row('frames', 'egl-device') ? $3 : NaN):($4/1024) with linespoints pointsize 0.3 title 'egl-device (+1.16 %)', \
     'soak.csv' skip 1 using (row('frames', 'egl-surfaceless') ? $3 : NaN):($4/1024) with linespoints pointsize 0.3 title 'egl-surfaceless (+0.10 %)', \
     'soak.csv' skip 1 using (row('frames', 'osmesa') ? $3 : NaN):($4/1024) with linespoints pointsize 0.3 title 'osmesa (+0.05 %)'
unset arrow 1
set title 'create/destroy cycles: builtin:cubes, 64x48, growth after warm-up in the key' noenhanced
set xlabel 'cycles'
plot 'soak.csv' skip 1 using (row('backend', 'software') ? $3 : NaN):($4/1024) with linespoints pointsize 0.3 title 'software backend (+0.00 %)', \
     'soak.csv' skip 1 using (row('target', 'software') ? $3 : NaN):($4/1024) with linespoints pointsize 0.3 title 'software target (+0.00 %)', \
     'soak.csv' skip 1 using (row('scene', 'software') ? $3 : NaN):($4/1024) with linespoints pointsize 0.3 title 'software scene (+0.00 %)', \
     'soak.csv' skip 1 using (row('backend', 'egl-device') ? $3 : NaN):($4/1024) with linespoints pointsize 0.3 title 'egl-device backend (+0.29 %)', \
     'soak.csv' skip 1 using (row('target', 'egl-device') ? $3 : NaN):($4/1024) with linespoints pointsize 0.3 title 'egl-device target (+0.05 %)', \
     'soak.csv' skip 1 using (row('scene', 'egl-device') ? $3 : NaN):($4/1024) with linespoints pointsize 0.3 title 'egl-device scene (+0.00 %)', \
     'soak.csv' skip 1 using (row('backend', 'egl-surfaceless') ? $3 : NaN):($4/1024) with linespoints pointsize 0.3 title 'egl-surfaceless backend (+0.01 %)', \
     'soak.csv' skip 1 using (row('target', 'egl-surfaceless') ? $3 : NaN):($4/1024) with linespoints pointsize 0.3 title 'egl-surfaceless target (+0.00 %)', \
     'soak.csv' skip 1 using (row('scene', 'egl-surfaceless') ? $3 : NaN):($4/1024) with linespoints pointsize 0.3 title 'egl-surfaceless scene (+0.00 %)', \
     'soak.csv' skip 1 using (row('backend', 'osmesa') ? $3 : NaN):($4/1024) with linespoints pointsize 0.3 title 'osmesa backend (+0.03 %)', \
     'soak.csv' skip 1 using (row('target', 'osmesa') ? $3 : NaN):($4/1024) with linespoints pointsize 0.3 title 'osmesa target (+0.96 %)', \
     'soak.csv' skip 1 using (row('scene', 'osmesa') ? $3 : NaN):($4/1024) with linespoints pointsize 0.3 title 'osmesa scene (+0.00 %)'
unset multiplot
