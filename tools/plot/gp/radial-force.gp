
# ---- radial displacement over normal contact force at one retainer (figures 4, 6, 8) ------------
# data columns: 1 time [s], 2 x [mm], 3 y [mm], 4 radial displacement [mm], 5 normal force [N],
# 6 in contact (1/0); contacts columns: 1 start [s], 2 end [s], 3-4 drawn extent [s]
set xrange [t0:t1]
set multiplot layout 2,1 margins 0.1,0.97,0.08,0.865 spacing 0,0.025 title what."\n".case_title
# optional plot elements (a curve without points would make gnuplot warn)
SHADE(top, key) = intervals > 0 ? sprintf("contacts using (($3+$4)/2):(%s/2):3:4:(0):(%s) with boxxyerror fs solid 0.55 noborder lc rgb '#f6b7a9' title '%s', ", top, top, key) : ""
CLEARANCE = (c == c) ? ", c with lines dt 3 lw 2 lc rgb '#333333' title 'clearance'" : ""

# top: radial displacement
set format x ''
unset xlabel
set ylabel 'radial displacement [mm]'
set yrange [0:RMAX]
set key at screen 0.535, 0.875 center bottom horizontal samplen 3 width 1
SHADE_TOP = SHADE("RMAX", "in contact")
plot @SHADE_TOP data using 1:4 with lines lw 1 lc rgb '#1f77b4' title 'radial displacement' @CLEARANCE, \
     NaN with lines lw 1 lc rgb '#d62728' title 'normal force', \
     NaN with lines dt 2 lw 1 lc rgb '#888888' title MARKER_KEY

# bottom: normal contact force
set format x '%g'
set xlabel 'time [s]'
set ylabel 'normal contact force [N]'
set yrange [0:FMAX]
unset key
SHADE_BOTTOM = SHADE("FMAX", "")
plot @SHADE_BOTTOM data using 1:5 with lines lw 1 lc rgb '#d62728' notitle

unset multiplot
