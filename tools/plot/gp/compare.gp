
# ---- radial displacement and normal contact force at one retainer, several files overlaid -----
# data columns: 1 time [s], 2 x [mm], 3 y [mm], 4 radial displacement [mm], 5 normal force [N],
# 6 in contact (1/0); file i is drawn in palette[slot[i]]
set xrange [t0:t1]
set multiplot layout 2,1 margins 0.1,0.97,0.08,0.865 spacing 0,0.025 title fig_title
CLEARANCE = (c == c) ? ", c with lines dt 3 lw 2 lc rgb '#333333' title 'clearance'" : ""

# top: radial displacement
set format x ''
unset xlabel
set ylabel 'radial displacement [mm]'
set yrange [0:RMAX]
set key at screen 0.535, 0.875 center bottom horizontal samplen 3 width 1
plot for [i=1:|data|] data[i] using 1:4 with lines lw 1.2 lc rgb palette[slot[i]] title label[i] @CLEARANCE

# bottom: normal contact force
set format x '%g'
set xlabel 'time [s]'
set ylabel 'normal contact force [N]'
set yrange [0:FMAX]
unset key
plot for [i=1:|data|] data[i] using 1:5 with lines lw 1.2 lc rgb palette[slot[i]] notitle

unset multiplot
