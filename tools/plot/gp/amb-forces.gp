
# ---- x and y force of each AMB against time ----------------------------------------------------
# data columns: 1 time [s], then Fx and Fy of AMB 0 [N], of AMB 1, ...
set xrange [t0:t1]
bottom = 60.0 / height          # fixed pixel margins
top = 1.0 - 100.0 / height
set multiplot layout words(amb_names),1 margins 0.1,0.97,bottom,top spacing 0,0.04 title "AMB forces on the rotor\n".case_title
set key at screen 0.535, top + 0.01 center bottom horizontal samplen 3 width 1
do for [a=1:words(amb_names)] {
    set ylabel word(amb_names, a).' force [N]'
    if (a == words(amb_names)) {
        set format x '%g'
        set xlabel 'time [s]'
    } else {
        set format x ''
        unset xlabel
    }
    plot data using 1:2*a with lines lw 1 lc rgb '#1f77b4' title 'Fx', \
         data using 1:2*a+1 with lines lw 1 lc rgb '#ff7f0e' title 'Fy', \
         NaN with lines dt 2 lw 1 lc rgb '#888888' title (a == 1 ? MARKER_KEY : '')
    unset key
}

unset multiplot
