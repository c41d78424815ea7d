
# scheduled changes (e.g. the unbalance steps): dashed vertical lines
do for [i=1:words(markers)] {
    t = real(word(markers, i))
    set arrow i from t, graph 0 to t, graph 1 nohead dt 2 lw 1 lc rgb '#888888' front
}
MARKER_KEY = words(markers) > 0 ? "scheduled change" : ""
