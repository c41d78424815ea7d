
# ---- bifurcation diagram -------------------------------------------------------------------------
# data columns: 1 the swept key, 2 the retainer node's radius [mm] once per revolution after the
# transient, 3 the point; one block per value of the other swept keys, titled by titles[i];
# clear: the radial clearance [mm]
set title "Bifurcation diagram: once-per-revolution radius at the retainer\n".case_title
if (logx) { set logscale x }
set xlabel xlabel
set ylabel 'radius at the retainer, once per revolution [mm]'
set yrange [0:*]
set autoscale xfix
set offsets graph 0.03, graph 0.03, 0, 0
set key outside right top vertical Left reverse samplen 2
CLEARANCE = has_clearance ? ", clear using 1:2 with lines dt 2 lw 2 lc rgb 'black' title 'clearance'" : ""
plot for [i=1:ngroups] data index (i-1) using 1:2 with points pt 7 ps 0.8 title titles[i] @CLEARANCE
