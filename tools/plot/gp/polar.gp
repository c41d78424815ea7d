
# ---- polar plot of the unbalance response ---------------------------------------------------------
# data: one block (index j - 1) per response node; columns 5 Re X [um], 6 Im X [um]
set title fig_title
set xlabel 'Re X [um]'
set ylabel 'Im X [um]'
set size ratio -1
set xzeroaxis lt 1 lw 1 lc rgb '#888888'
set yzeroaxis lt 1 lw 1 lc rgb '#888888'
set key outside right top vertical
plot for [j=1:|label|] data index j-1 using 5:6 with lines lw 2 dt 1+(j-1)%2 lc rgb palette[(j-1)%8+1] title label[j]
