# Error against cost per solver kind, one panel per scene (docs/accuracy.md).
# Input: the CSV of `tradeoff pareto`; every setting that stayed finite.
set datafile separator ","
set terminal pngcairo size 1400,1000 noenhanced font ",10"
set output out
set multiplot layout 2,2
set logscale xy
set xlabel "wall time per 1/60 s of simulated time (ms, shared noisy machine)"
set ylabel "RMS position error against converged CG at 1/960 s (m)"
set key bottom left
set xrange [0.05:5000]
set yrange [1e-6:1]
do for [scene in "hanging falling_flat flag_in_wind draped_sphere"] {
    set title scene
    plot for [kind in "JACOBI CHEBYSHEV PCG CG DEFAULT"] \
        data using (strcol(1) eq scene && strcol(2) eq kind ? $7 : 1/0):($8 > 0 && $8 < 1e3 ? $8 : 1/0) \
        with points pt 7 ps 0.8 title kind
}
unset multiplot
