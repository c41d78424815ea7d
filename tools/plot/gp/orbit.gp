
# ---- orbit at one retainer (the paper's figures 3, 5, 7) ---------------------------------------
# data columns: 1 time [s], 2 x [mm], 3 y [mm], 4 radial displacement [mm], 5 normal force [N],
# 6 in contact (1/0)
set title what."\n".case_title
set size ratio -1              # equal scales on x and y
set xrange [-L:L]
set yrange [-L:L]
set xlabel 'x [mm]'
set ylabel 'y [mm]'
set key outside below center horizontal
set samples 721
# optional plot elements (a curve without points would make gnuplot warn)
CIRCLE = (c == c) ? "'+' using (c*cos(2*pi*$0/720)):(c*sin(2*pi*$0/720)) with lines lw 2 lc rgb '#333333' title sprintf('clearance %.3g mm', c), " : ""
CONTACT = in_contact ? ", data using ($6 > 0 ? $2 : NaN):3 with points pt 7 ps 0.5 lc rgb '#d62728' title 'in contact'" : ""
plot @CIRCLE data using 2:3 with lines lw 0.8 lc rgb '#1f77b4' title 'orbit' @CONTACT
