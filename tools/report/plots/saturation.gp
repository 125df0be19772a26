# Figure 2: achieved against commanded acceleration, with the config's predictions.
load dir.'/values.gp'
load 'common.gp'
columns = sweep_count > 1 ? 2 : 1
rows = (sweep_count + columns - 1) / columns
set terminal pngcairo size 1400, 80 + 430 * rows font ',11' enhanced
set output dir.'/saturation.png'
set multiplot layout rows, columns title 'Achieved against commanded acceleration (ground truth; VISION for wheel-speed ramps)'
set xlabel 'commanded ramp (m/s^2)'
set ylabel 'achieved (m/s^2)'
set key top left
do for [i=0:sweep_count-1] {
  type = value(sprintf('sweep_type%d', i))
  pred = value(sprintf('sweep_pred%d', i))
  onboard = value(sprintf('sweep_onboard%d', i))
  set title type noenhanced
  set xrange [0:*]
  set yrange [*:*]
  plot x with lines dt 3 lc rgb 'gray' title 'achieved = commanded', \
       pred with lines dt 2 lw 2 lc rgb 'black' title sprintf('predicted limit %.2f m/s^2', pred), \
       onboard with lines dt 4 lw 1.5 lc rgb '#2ca02c' title sprintf('on-board limit %.2f m/s^2', onboard), \
       dir.'/sweep_'.type.'.dat' index 0 using 1:2 with linespoints pt 7 ps 1.2 lc rgb '#1f77b4' title 'wheel-speed commands', \
       dir.'/sweep_'.type.'.dat' index 0 using 1:3:(2*$4) with yerrorbars pt 6 ps 1.2 lc rgb '#d62728' title 'the same from VISION (±2 standard errors)', \
       dir.'/sweep_'.type.'.dat' index 1 using 1:2 with linespoints pt 5 ps 1.0 lc rgb '#2ca02c' title 'velocity commands'
}
unset multiplot
