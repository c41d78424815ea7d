
# ---- Nyquist curve of the open loop L_j per controlled axis ---------------------------------------
# data columns: per axis j (from 1) column 5j-2 Re L, 5j-1 Im L. The circles of radius 1/3, 1/4,
# 1/5 around -1 are where |S| = 3, 4, 5 (ISO 14839-3 zone limits): a curve outside the circle of
# radius 1/3 has a peak sensitivity below 3 (zone A).
set title fig_title
set xlabel 'Re L'
set ylabel 'Im L'
set size ratio -1
set xrange [-3:1]
set yrange [-2:2]
set key outside right top vertical
set parametric
set trange [0:2*pi]
set samples 400
plot for [j=1:|label|] data using (column(5*j-2)):(column(5*j-1)) with lines lw 2 dt 1+(j-1)%2 lc rgb palette[(j-1)%8+1] title label[j], \
     -1 + cos(t)/3, sin(t)/3 with lines dt 2 lc rgb '#2ca02c' title '|S| = 3', \
     -1 + cos(t)/4, sin(t)/4 with lines dt 2 lc rgb '#ff7f0e' title '|S| = 4', \
     -1 + cos(t)/5, sin(t)/5 with lines dt 2 lc rgb '#d62728' title '|S| = 5', \
     '+' using (-1):(0) with points pt 2 ps 2 lc rgb 'black' title '-1'
