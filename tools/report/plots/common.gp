# Shared settings of every report figure. Called with: gnuplot -e "dir='OUT'" X.gp
set terminal pngcairo size 1400,1000 font ',11' enhanced
set grid lc rgb '#dddddd'
set key top left box opaque
set datafile missing '?'
