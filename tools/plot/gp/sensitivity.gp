
# ---- sensitivity |S_j| per controlled axis with the ISO 14839-3 zones ------------------------------
# data columns: 1 f [Hz], then per axis j (from 1) column 5j-3 |S|
set title fig_title
set xlabel 'frequency [Hz]'
set ylabel '|S| (linear)'
set logscale x
set xrange [fmin:fmax]
set key outside right top vertical
# zone bands (ISO 14839-3:2006, "Evaluation of stability margin"): A < 3 <= B < 4 <= C < 5 <= D
set object 1 rect from graph 0, first 0 to graph 1, first 3 fc rgb '#e0f3e0' fs solid 1.0 noborder behind
set object 2 rect from graph 0, first 3 to graph 1, first 4 fc rgb '#fff6d0' fs solid 1.0 noborder behind
set object 3 rect from graph 0, first 4 to graph 1, first 5 fc rgb '#ffe0c0' fs solid 1.0 noborder behind
set object 4 rect from graph 0, first 5 to graph 1, graph 1 fc rgb '#ffd0d0' fs solid 1.0 noborder behind
set label 11 'A' at graph 0.01, first 1.5 front
set label 12 'B' at graph 0.01, first 3.5 front
set label 13 'C' at graph 0.01, first 4.5 front
set label 14 'D' at graph 0.01, first 5.5 front
set yrange [0:6.5<*]
plot for [j=1:|label|] data using 1:(column(5*j-3)) with lines lw 2 dt 1+(j-1)%2 lc rgb palette[(j-1)%8+1] title label[j]
