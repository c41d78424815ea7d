
# ---- Campbell diagram ----------------------------------------------------------------------------
# data columns: 1 speed [rad/s], 2 damped natural frequency [Hz], 3 whirl (1 forward, -1 backward,
# 0 mixed), one block per branch; crit: the critical speeds, same columns
set title "Campbell diagram\n".case_title
if (strlen(critical_text) > 0) {
    # beside the plot, under the key (labels at the points would overlap where forward and
    # backward crossings lie close together)
    set label 1 critical_text at screen 0.745, screen 0.6 left front font ',10'
}
set xlabel 'rotor speed [rad/s]'
set ylabel 'damped natural frequency [Hz]'
set xrange [smin:smax]
set yrange [0:*]
set lmargin at screen 0.08
set rmargin at screen 0.72
set key at screen 0.74, screen 0.9 left top vertical Left reverse samplen 2
set samples 400
# optional plot elements (a curve without points would make gnuplot warn)
MIXED = has_mixed ? ", data using 1:(abs($3) <= 0.5 ? $2 : NaN) with points pt 9 ps 0.7 lc rgb '#7f7f7f' title 'mixed / planar'" : ""
CRITICAL = strlen(critical_text) > 0 ? ", crit using 1:2 with points pt 6 ps 2.2 lw 2 lc rgb 'black' title 'critical speed'" : ""
plot data using 1:2 with lines lw 1 lc rgb '#c0c0c0' title 'branch', \
     x/(2*pi) with lines dt 2 lw 2 lc rgb 'black' title '1x (synchronous)', \
     data using 1:($3 > 0.5 ? $2 : NaN) with points pt 7 ps 0.7 lc rgb '#1f77b4' title 'forward whirl', \
     data using 1:($3 < -0.5 ? $2 : NaN) with points pt 5 ps 0.7 lc rgb '#d62728' title 'backward whirl' @MIXED @CRITICAL
