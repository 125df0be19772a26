# Figure 4: flat-kick roll-out against the model; chip kicks against ballistic arcs.
load 'common.gp'
set output dir.'/ball_rollout.png'
set terminal pngcairo size 1400,700
set multiplot layout 1, 2 title 'Flat kicks: ball speed over time and roll-out distance against the config model'
set xlabel 'time since the kick (s)'
set ylabel 'ball speed (m/s)'
set key top right
plot dir.'/kick_trajectories.dat' using 1:3 with lines lw 2 lc rgb '#1f77b4' title 'simulated (ground truth)', \
     dir.'/kick_model.dat' using 1:3 with lines dt 2 lw 2 lc rgb 'black' title 'model: slide, then roll'
set xlabel 'kick speed (m/s)'
set ylabel 'roll-out distance (m)'
set key top left
plot dir.'/kicks.dat' using 1:3 with linespoints dt 2 lw 2 pt 6 ps 1.5 lc rgb 'black' title 'model', \
     dir.'/kicks.dat' using 1:2 with points pt 7 ps 1.2 lc rgb '#1f77b4' title 'simulated'
unset multiplot

set output dir.'/ball_chip.png'
set terminal pngcairo size 1400,600
set xlabel 'horizontal distance from the kicker (m)'
set ylabel 'height of the ball above the carpet (m)'
set title 'Chip kicks at 45 deg: simulated flight against the ballistic arc'
set size ratio -1
set key top right
plot dir.'/chip_trajectories.dat' using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'simulated (with bounces)', \
     dir.'/chip_model.dat' using 1:2 with lines dt 2 lw 2 lc rgb 'black' title 'ballistic, no drag'
