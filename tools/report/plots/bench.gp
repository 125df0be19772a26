# Figure 5: physics benchmark, simulated seconds per wall second (as fast as possible).
load 'common.gp'
set terminal pngcairo size 1400,600 font ',11'
set output dir.'/bench.png'
set style data histograms
set style histogram clustered gap 1
set style fill solid 0.8 border -1
set boxwidth 0.9
set title 'Physics benchmark at 240 Hz, as fast as possible (higher is faster; log scale)'
set ylabel 'simulated seconds per wall second'
set logscale y
set yrange [1:*]
set xtics noenhanced
set key top right
plot dir.'/bench.dat' using 4:xtic(sprintf('%s %s', strcol(1), strcol(3))) title 'ubersim server (messages published)', \
     '' using 6 title 'bare ODE, same scene'
