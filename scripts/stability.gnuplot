# Stability map (docs/stability.md): class per solver over step (x) and
# gamma = dt^2 k / m (y), resolution 32. 3 holds, 2 stretches > 10 %,
# 1 gains energy, 0 blows up.
set datafile separator ","
set terminal pngcairo size 1500,420 noenhanced font ",10"
set output out
set multiplot layout 1,5
set logscale xy
set xlabel "dt (s)"
set ylabel "gamma"
set cbrange [0:3]
set palette defined (0 "#c0392b", 1 "#e67e22", 2 "#f1c40f", 3 "#27ae60")
unset colorbox
do for [kind in "EXPLICIT JACOBI CHEBYSHEV PCG DEFAULT"] {
    set title kind
    plot data using (strcol(1) eq kind && $3 == 32 ? $5 : 1/0):7:10 with points pt 5 ps 1.6 palette notitle
}
unset multiplot
