
# ---- Bode plot of the unbalance response ---------------------------------------------------------
# data: one block (index j - 1) per response node; columns 1 speed [rad/s], 2 major semi-axis [um],
# 4 phase of x [deg]; the operating range (op_min, op_max; -1: none) shaded; AF labels at the peaks
set multiplot layout 2, 1 title fig_title
set xrange [smin:smax]
set key outside right top vertical
if (op_min >= 0) {
    set object 1 rect from op_min, graph 0 to op_max, graph 1 fc rgb '#e8e8e8' fs solid 1.0 noborder behind
}
set ylabel 'major semi-axis [um] (0-peak)'
set yrange [0:*]
plot for [j=1:|label|] data index j-1 using 1:2 with lines lw 2 dt 1+(j-1)%2 lc rgb palette[(j-1)%8+1] title label[j]
unset label
set xlabel 'rotor speed [rad/s]'
set ylabel 'phase of x [deg]'
set yrange [-180:180]
set ytics 90
plot for [j=1:|label|] data index j-1 using 1:4 with lines lw 2 dt 1+(j-1)%2 lc rgb palette[(j-1)%8+1] title label[j]
unset multiplot
