
# ---- regime map ----------------------------------------------------------------------------------
# data columns: 1 x key, 2 y key (0 with one swept key), 3 half width, 4 half height, 5 regime code
# (0 failed, 1 free, 2 rub, 3 bounce, 4 backward whirl), 6 point; codes/names/colors: the regimes
# present
set title "Regime map\n".case_title
set xlabel xlabel
set ylabel ylabel
if (!has_y) { unset ytics }
set key outside right top vertical Left reverse samplen 2
set style fill solid 0.9 border lc rgb 'white'
plot for [i=1:nregimes] data using 1:($5 == codes[i] ? $2 : NaN):3:4 with boxxyerror lc rgb colors[i] title names[i]
