# Stability map (docs/stability.md): class per solver over step (x) and
# gamma = dt^2 k / m (y), resolution 32. 3 holds, 2 stretches > 10 %,
# 1 gains energy, 0 blows up.
set datafile separator ","
set terminal pngcairo size 1500,470 noenhanced font ",10"
set output out
set multiplot layout 1,5 title "32x32 cloth falling flat for 0.5 s: where each solver kind holds"
set logscale xy
set format x "1e%L"
set format y "1e%L"
set xlabel "dt (s)"
set ylabel "gamma = dt^2 k / m"
set xrange [5e-4:0.2]
set yrange [0.01:1e9]
set key top left samplen 1 font ",8"
colours = "#c0392b #e67e22 #f1c40f #27ae60"
name(c) = c == 3 ? "holds" : c == 2 ? "stretches > 10 %" : c == 1 ? "gains energy" : "blows up"
do for [kind in "EXPLICIT JACOBI CHEBYSHEV PCG DEFAULT"] {
    set title kind
    plot for [c=3:0:-1] data using (strcol(1) eq kind && $3 == 32 && $10 == c ? $5 : 1/0):7 \
        with points pt 5 ps 1.6 lc rgb word(colours, c + 1) title (kind eq "EXPLICIT" ? name(c) : "")
}
unset multiplot
