# Figure 1: the 2 m/s^2 ramps, speed and distance against time, every robot type.
load dir.'/values.gp'
load 'common.gp'
columns = ramp_count > 1 ? 2 : 1
rows = (ramp_count + columns - 1) / columns
set terminal pngcairo size 1400, 80 + 430 * rows font ',11' enhanced

set key bottom right
do for [quantity in "speed position"] {
  set output dir.'/ramp_'.quantity.'.png'
  set multiplot layout rows, columns title (quantity eq 'speed' ? \
      'Forward speed during a 2 m/s^2 ramp: ground truth, VISION and the ideal curve' : \
      'Distance travelled during a 2 m/s^2 ramp: ground truth, VISION and the ideal curve')
  col = quantity eq 'speed' ? 3 : 2
  set xlabel 'time since the first command (s)'
  set ylabel (quantity eq 'speed' ? 'speed along the start heading (m/s)' : 'distance along the start heading (m)')
  do for [i=0:ramp_count-1] {
    type = value(sprintf('ramp_type%d', i))
    set title type noenhanced
    plot dir.'/ramp_'.type.'_vision.dat' using 1:col with points pt 7 ps 0.5 lc rgb '#d62728' \
           title 'VISION, every trial', \
         dir.'/ramp_'.type.'_truth.dat' using 1:col with lines lw 1.5 lc rgb '#1f77b4' \
           title 'ground truth, every trial', \
         dir.'/ramp_'.type.'_ideal.dat' using 1:col with lines dt 2 lw 2 lc rgb 'black' \
           title 'ideal: 2 m/s^2, then the config top speed'
  }
  unset multiplot
}
