
# ---- a summary quantity against a swept key ------------------------------------------------------
# data columns: 1 the swept key, 2 the quantity, 3 the point; one block (gnuplot index) per value of
# the other swept keys, titled by titles[i]
set title ylabel." against ".xlabel."\n".case_title
if (logx) { set logscale x }
if (logy) { set logscale y }
set xlabel xlabel
set ylabel ylabel
set key outside right top vertical Left reverse samplen 2
set autoscale xfix
set offsets graph 0.03, graph 0.03, graph 0.05, graph 0.05
# failed or not-run points (nfailed, the last block) have no value: a cross at the foot, on the y2
# axis so that the y range and its log scale are those of the values
set y2range [0:1]
unset y2tics
marks = nfailed > 0 ? sprintf(', data index %d using 1:(0.03) axes x1y2 with points pt 2 ps 1.6 lw 2 ' . \
                                'lc rgb "#7f7f7f" title "failed or not run"', ngroups) : ''
plot for [i=1:ngroups] data index (i-1) using 1:2 with linespoints lw 2 pt 7 ps 0.9 title titles[i] @marks
