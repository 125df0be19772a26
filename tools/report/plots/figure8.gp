# Figure 3: figure-8 paths (VISION over the intended curve) and the errors over time.
load dir.'/values.gp'
load 'common.gp'
set terminal pngcairo size 1400,650 font ',11'
set output dir.'/figure8_paths.png'
set multiplot layout 1, figure8_count title 'Figure-8 at 0.8 m/s: the path seen on VISION over the intended one'
set size ratio -1
set xlabel 'x (m)'
set ylabel 'y (m)'
set key outside bottom center horizontal
do for [i=0:figure8_count-1] {
  label = value(sprintf('figure8_label%d', i))
  period = value(sprintf('figure8_period%d', i))
  set title 'emulator profiles: '.label noenhanced
  plot dir.'/figure8_path.dat' using 1:2 with lines lw 3 lc rgb 'black' title 'intended', \
       dir.'/figure8_'.label.'_truth.dat' using ($1 >= period ? $2 : 1/0):3 with lines lw 1 lc rgb '#1f77b4' title 'ground truth (laps 2..)', \
       dir.'/figure8_'.label.'_vision.dat' using ($1 >= period ? $2 : 1/0):3 with points pt 7 ps 0.4 lc rgb '#d62728' title 'VISION (laps 2..)'
}
unset multiplot

set output dir.'/figure8_error.png'
set size noratio
set terminal pngcairo size 1400,700
set multiplot layout 1, 2 title 'Figure-8 errors over time (the first lap starts from rest)'
set key inside top right
set xlabel 'time (s)'
set ylabel 'tracking error (m)'
set title 'tracking error: to the reference point at the same time'
plot for [i=0:figure8_count-1] dir.'/figure8_'.value(sprintf('figure8_label%d', i)).'_error.dat' \
     using 1:2 with lines lw 1.5 title value(sprintf('figure8_label%d', i)) noenhanced
set ylabel 'path error (m)'
set title 'path error: to the nearest point of the curve'
plot for [i=0:figure8_count-1] dir.'/figure8_'.value(sprintf('figure8_label%d', i)).'_error.dat' \
     using 1:3 with lines lw 1.5 title value(sprintf('figure8_label%d', i)) noenhanced
unset multiplot
