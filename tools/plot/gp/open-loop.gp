
# ---- Bode diagram of the open loop L_j = 1/S_j - 1 per controlled axis ----------------------------
# data columns: 1 f [Hz], then per axis j (from 1) column 5j |L| [dB], 5j+1 arg L [deg]
set multiplot layout 2,1 title fig_title
set logscale x
set xrange [fmin:fmax]
set key outside right top vertical
set ylabel '|L| [dB]'
unset xlabel
plot for [j=1:|label|] data using 1:(column(5*j)) with lines lw 2 dt 1+(j-1)%2 lc rgb palette[(j-1)%8+1] title label[j], \
     0 with lines dt 2 lc rgb 'black' notitle
set xlabel 'frequency [Hz]'
set ylabel 'arg L [deg]'
set yrange [-180:180]
set ytics 90
plot for [j=1:|label|] data using 1:(column(5*j+1)) with lines lw 2 dt 1+(j-1)%2 lc rgb palette[(j-1)%8+1] title label[j]
unset multiplot
