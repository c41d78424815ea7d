# ---- terminal and common style ----------------------------------------------------------------
# The script picks pngcairo when this gnuplot has it, else libgd's png, so a copied script works
# with any gnuplot build (5.2 or newer). No 'set encoding': the png, pngcairo and svg terminals
# take the UTF-8 of titles and names as it is, while 'set encoding utf8' makes gnuplot warn in
# the C/POSIX locale.
if (format eq 'svg') {
    set terminal svg size width,height dynamic font 'Sans,12' linewidth 1.2 background rgb 'white'
} else {
    if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {
        set terminal pngcairo size width,height font 'Sans,11' linewidth 1.2 noenhanced
    } else {
        set terminal png size width,height font 'Sans,10' linewidth 1.2 noenhanced
    }
}
set output figure.'.'.format
set termoption noenhanced    # names and titles are printed as written
set grid lc rgb '#dddddd' lw 1
set border lw 1
set key noautotitle
set datafile missing 'NaN'
