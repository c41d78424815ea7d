
# ---- dynamic compliance at each AMB axis, every loop closed ---------------------------------------
# data columns: 1 f [Hz], then |x/F| [m/N] per AMB axis (column j+1)
set title fig_title
set xlabel 'frequency [Hz]'
set ylabel 'compliance |x/F| [m/N]'
set logscale xy
set format y '%.0e'
set xrange [fmin:fmax]
set key outside right top vertical
plot for [j=1:|label|] data using 1:(column(j+1)) with lines lw 2 dt 1+(j-1)%2 lc rgb palette[(j-1)%8+1] title label[j]
