
# ---- regime map ----------------------------------------------------------------------------------
# data columns: 1 x key, 2 y key (0 with one swept key), 3-4 the tile's left and right edges, 5-6
# its bottom and top edges, 7 regime code (0 failed, 1 free, 2 rub, 3 bounce, 4 backward whirl),
# 8 point; codes/names/colors: the regimes present
set title "Regime map\n".case_title
if (logx) { set logscale x }
if (logy) { set logscale y }
set xlabel xlabel
set ylabel ylabel
if (!has_y) { unset ytics }
set key outside right top vertical Left reverse samplen 2
set style fill solid 0.9 border lc rgb 'white'
set autoscale fix
plot for [i=1:nregimes] data using 1:($7 == codes[i] ? $2 : NaN):3:4:5:6 with boxxyerror lc rgb colors[i] title names[i]
