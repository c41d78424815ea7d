
# ---- lateral mode shapes along the rotor ---------------------------------------------------------
# data columns: 1 axial position [m] (or node number), then one column per mode (mode 1 in column 2)
set title fig_title
set xlabel x_label
set ylabel 'normalised displacement (largest = 1)'
set yrange [-1.1:1.1]
set key outside right top vertical
set xzeroaxis lt 1 lw 1 lc rgb '#888888'
# even modes dashed: forward/backward pairs share a shape and would hide each other
plot for [i=1:|label|] data using 1:(column(i+1)) with linespoints lw 2 pt 7+2*((i-1)%3) ps 0.8 dt 1+(i-1)%2 \
     lc rgb palette[(i-1)%8+1] title label[i]
