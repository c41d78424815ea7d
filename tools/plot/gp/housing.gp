# ---- the housing's prescribed motion against time: acceleration (top), displacement (bottom) -----
# data columns: 1 time [s], 2 ax [g], 3 ay [g], 4 x [mm], 5 y [mm], with a body (body = 1) 6, 7 its x, y [mm]
set xrange [t0:t1]
set multiplot layout 2,1 margins 0.1,0.97,0.08,0.865 spacing 0,0.025 title "Housing motion\n".case_title
set key at screen 0.535, 0.875 center bottom horizontal samplen 3 width 1

# top: acceleration, in g
set format x ''
unset xlabel
set ylabel 'housing acceleration [g]'
if (still) { set yrange [-1:1] }
plot data using 1:2 with lines lw 1 lc rgb '#1f77b4' title 'x', \
     data using 1:3 with lines lw 1 lc rgb '#ff7f0e' title 'y', \
     NaN with lines dt 3 lw 1 lc rgb '#1f77b4' title (body ? 'body x (below)' : ''), \
     NaN with lines dt 3 lw 1 lc rgb '#ff7f0e' title (body ? 'body y (below)' : ''), \
     NaN with lines dt 2 lw 1 lc rgb '#888888' title MARKER_KEY

# bottom: displacement (and a housing body's, relative to the base, dotted: columns 6, 7)
set format x '%g'
set xlabel 'time [s]'
set ylabel 'housing displacement [mm]'
set autoscale y
unset key
if (body) {
    plot data using 1:4 with lines lw 1 lc rgb '#1f77b4' notitle, \
         data using 1:5 with lines lw 1 lc rgb '#ff7f0e' notitle, \
         data using 1:6 with lines dt 3 lw 1 lc rgb '#1f77b4' notitle, \
         data using 1:7 with lines dt 3 lw 1 lc rgb '#ff7f0e' notitle
} else {
    plot data using 1:4 with lines lw 1 lc rgb '#1f77b4' notitle, \
         data using 1:5 with lines lw 1 lc rgb '#ff7f0e' notitle
}

unset multiplot
