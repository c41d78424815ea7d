
# ---- the drop report's figure (touchdown report) -------------------------------------------------
# data columns: 1 time [s], 2 rotor speed [rad/s], then for retainer k = 0, 1, ... five columns from
# 3 + 5k: normal contact force [N], race speed [rad/s], x [mm], y [mm], race temperature above
# ambient [K]; NaN: not in the file (has_speed, has_races, has_temperature say which are)
FN(k) = 3 + 5*k
set multiplot layout 2,2 margins 0.07,0.97,0.07,0.9 spacing 0.08,0.1 title case_title
set key top right samplen 2
set xlabel 'time [s]'

# a panel with nothing to draw says why (a curve without points would make gnuplot fail)
NOTHING(why) = sprintf("set label 1 '%s' at graph 0.5, 0.5 center; unset key; plot [0:1][0:1] NaN notitle; unset label 1; set key top right", why)

# top left: normal contact force of each retainer
set ylabel 'normal contact force [N]'
if (nret > 0) {
    plot for [k=0:nret-1] data using 1:FN(k) with lines lw 0.8 title sprintf('retainer %d', k)
} else {
    eval NOTHING('no retainer in this file')
}

# top right: the rotor's speed and the races'
set ylabel 'speed [rad/s]'
set key bottom right
# a prescribed speed is not in the file, nor are the speeds of races that are not bodies
ROTOR = has_speed ? "data using 1:2 with lines lw 1.5 lc rgb '#333333' title 'rotor'" : ""
RACES = has_races ? "for [k=0:nret-1] data using 1:FN(k)+1 with lines lw 0.8 title sprintf('race %d', k)" : ""
if (has_speed || has_races) {
    eval "plot ".ROTOR.((has_speed && has_races) ? ", " : "").RACES
} else {
    eval NOTHING('speeds: not in this file (a prescribed speed, no race bodies)')
}

# bottom left: race temperatures (the retainers' thermal model), or why there are none
set key top right
set ylabel 'race temperature rise [K]'
if (has_temperature) {
    plot for [k=0:nret-1] data using 1:FN(k)+4 with lines lw 1 title sprintf('race %d', k)
} else {
    eval NOTHING('race temperature: not in this file')
}

# bottom right: the orbit at each retainer, the clearance circles dashed
set size ratio -1
set xlabel 'x [mm]'
set ylabel 'y [mm]'
set xrange [-L:L]
set yrange [-L:L]
set samples 361
if (nret > 0) {
    plot for [k=0:nret-1] data using FN(k)+2:FN(k)+3 with lines lw 0.6 title sprintf('retainer %d', k), \
         for [k=1:nret] '+' using (clearance[k]*cos(2*pi*$0/360)):(clearance[k]*sin(2*pi*$0/360)) \
             with lines dt 2 lw 1.5 lc rgb '#333333' notitle
} else {
    eval NOTHING('no retainer: no orbit at a retainer')
}
unset multiplot
