# Figure 6: share of one core the process set uses in real time.
load 'common.gp'
set terminal pngcairo size 1400,600 font ',11'
set output dir.'/cpu.png'
set style data histograms
set style histogram rowstacked
set style fill solid 0.8 border -1
set boxwidth 0.6
set title 'Share of one core in real time: physics + vision + radio (demo teams not counted); dashed: 10 % target for 2 x 11'
set ylabel '% of one core'
set yrange [0:*]
set xtics noenhanced
set key top left
set arrow from graph 0, first 10 to graph 1, first 10 nohead dt 2 lw 2 lc rgb 'red'
plot dir.'/cpu.dat' using 3:xtic(1) title 'physics', '' using 4 title 'vision', '' using 5 title 'radio'
