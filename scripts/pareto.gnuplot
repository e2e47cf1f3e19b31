# Error against cost per solver kind, one panel per scene (docs/accuracy.md):
# every setting that stayed finite as a point, and each kind's own Pareto
# front (no setting of that kind is both cheaper and more accurate) as a
# line. Input: the CSV of `tradeoff pareto` (column 15: on its kind's front).
# Variables: data, out, res (the resolution, for the title).
set datafile separator ","
set terminal pngcairo size 1400,1000 noenhanced font ",10"
set output out
set multiplot layout 2,2 title sprintf("%sx%s cloth, 1 kg, 1e3 N/m: RMS error against cost", res, res)
set logscale xy
set format x "1e%L"
set format y "1e%L"
set xlabel "wall time per 1/60 s of simulated time (ms, shared noisy machine)"
set ylabel "RMS position error against converged CG at 1/960 s (m)"
set key bottom left Left reverse
set xrange [0.01:10000]
set yrange [1e-6:1]
kinds = "JACOBI CHEBYSHEV PCG CG DEFAULT"
do for [scene in "hanging falling_flat flag_in_wind draped_sphere"] {
    set title scene
    plot for [i=1:words(kinds)] \
        data using (strcol(1) eq scene && strcol(2) eq word(kinds, i) ? $7 : 1/0):($8 > 0 && $8 < 1e3 ? $8 : 1/0) \
        with points pt 7 ps 0.7 lc i title word(kinds, i), \
        for [i=1:words(kinds)] \
        data using (strcol(1) eq scene && strcol(2) eq word(kinds, i) && $15 == 1 ? $7 : 1/0):($8) \
        smooth unique with lines lw 2 lc i notitle
}
unset multiplot
