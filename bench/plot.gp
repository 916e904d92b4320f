# Plots of a benchmark run: gnuplot -e "dir='results'" bench/plot.gp
# Reads DIR/*.csv (written by wavetrace_bench) and writes DIR/*.svg.
if (!exists("dir")) dir = "results"
set datafile separator ","
set terminal svg size 720,400 font "sans,12" background rgb "white"
set key top left
set grid ytics

# Speed per scene and engine.
set output dir."/engines.svg"
set title "Camera paths per second (median of interleaved repetitions)"
set ylabel "Mpaths/s"
set style data histograms
set style histogram clustered gap 1
set style fill solid 0.8 border -1
set boxwidth 0.9
set xtics rotate by -40 font ",10"
plot dir."/engines.csv" using 6:xtic(strcol(1)."\n".strcol(2)." thr") title "megakernel", \
     "" using 7 title "wavefront", "" using 18 title "megakernel on Embree", \
     "" using 19 title "wavefront on Embree"

# The wavefront against the megakernel (ours) and against a plain Embree path tracer.
set output dir."/engines-ratio.svg"
set title "Wavefront speed over megakernel speed (median; target 1.3)"
set ylabel "ratio"
set yrange [0:1.4]
plot dir."/engines.csv" using 11:xtic(strcol(1)."\n".strcol(2)." thr") title "wavefront / megakernel", \
     "" using 22 title "wavefront / megakernel on Embree", 1.3 with lines dt 2 lc rgb "grey" title "target"

# Wavefront speed against the wave size (paths per thread).
set autoscale y
set xtics norotate font ",12"
set output dir."/waves.svg"
set style data linespoints
set logscale x 2
set title "Wavefront / megakernel against wave size (all threads)"
set xlabel "paths per wave (per thread)"
set ylabel "wavefront / megakernel"
plot dir."/waves.csv" using (strcol(1) eq "cornell" ? column(7) : 1/0):6 title "cornell", \
     "" using (strcol(1) eq "dragon" ? column(7) : 1/0):6 title "dragon"
unset logscale x
unset xlabel
set style data histograms

# Our BVH against Embree, single thread.
set output dir."/bvh.svg"
set title "Single-ray traversal, one thread: ours vs Embree"
set ylabel "Mrays/s"
plot dir."/bvh.csv" using (column(3) == 1 ? column(5) : 1/0):xtic(strcol(1)."\n".strcol(2)) title "ours", \
     "" using (column(3) == 1 ? column(6) : 1/0) title "Embree rtcIntersect1/rtcOccluded1"

# Coherent primary rays, one thread: our 8-ray packets against Embree's 16-ray packets.
set output dir."/bvh-packets.svg"
set title "Primary rays in packets, one thread: ours (8 rays) vs Embree (16 rays)"
set ylabel "Mrays/s"
plot dir."/bvh.csv" using (column(3) == 1 && strcol(2) eq "primary" ? column(10) : 1/0):xtic(1) title "ours, packets", \
     "" using (column(3) == 1 && strcol(2) eq "primary" ? column(9) : 1/0) title "Embree rtcIntersect16", \
     "" using (column(3) == 1 && strcol(2) eq "primary" ? column(5) : 1/0) title "ours, single rays"

# Single rays against scene size (the dragon grown from 10^4 to 10^7 triangles), one thread.
set output dir."/scene-size.svg"
set style data linespoints
set logscale x 10
set xtics auto
set title "Single rays against scene size, one thread: ours vs Embree"
set xlabel "triangles"
set ylabel "Mrays/s"
plot for [b in "primary diffuse shadow"] dir."/scene_size.csv" \
         using (column(3) == 1 && strcol(2) eq b ? column(1) : 1/0):5 title "ours, ".b, \
     for [b in "primary diffuse shadow"] dir."/scene_size.csv" \
         using (column(3) == 1 && strcol(2) eq b ? column(1) : 1/0):6 title "Embree, ".b dt 2
unset logscale x
unset xlabel
set style data histograms

# Thread scaling.
set output dir."/scaling.svg"
set style data linespoints
set title "Speed-up over one thread"
set xlabel "threads"
set ylabel "speed-up"
set xtics 1
plot dir."/scaling.csv" using (strcol(1) eq "cornell" && strcol(2) eq "megakernel" ? column(3) : 1/0):6 title "cornell, megakernel", \
     "" using (strcol(1) eq "cornell" && strcol(2) eq "wavefront" ? column(3) : 1/0):6 title "cornell, wavefront", \
     "" using (strcol(1) eq "dragon" && strcol(2) eq "megakernel" ? column(3) : 1/0):6 title "dragon, megakernel", \
     "" using (strcol(1) eq "dragon" && strcol(2) eq "wavefront" ? column(3) : 1/0):6 title "dragon, wavefront", \
     x title "ideal" dt 2 lc rgb "grey"

# Convergence: relative MSE against time, log-log, one plot per scene.
set logscale xy
set xlabel "render time (s)"
set ylabel "relative MSE"
set key top right
set xtics auto
do for [s in "cornell veach-mis"] {
    set output dir."/convergence-".s.".svg"
    set title "Convergence on ".s
    plot for [st in "bsdf light mixture nee mis"] dir."/convergence.csv" \
        using (strcol(1) eq s && strcol(2) eq st ? column(4) : 1/0):5 title st
}

# Error against time per engine and sampler, log-log, one plot per scene (the megakernel dashed).
do for [s in "cornell veach-mis dragon-envmap cornell-glass mitsuba-pointlight"] {
    set output dir."/error-time-".s.".svg"
    set title "Relative MSE against render time on ".s
    plot for [sm in "independent sobol zsobol"] dir."/error_time.csv" \
        using (strcol(1) eq s && strcol(2) eq "wavefront" && strcol(3) eq sm ? column(5) : 1/0):6 \
        with linespoints lw 2 title "wavefront, ".sm, \
         for [sm in "independent sobol zsobol"] dir."/error_time.csv" \
        using (strcol(1) eq s && strcol(2) eq "megakernel" && strcol(3) eq sm ? column(5) : 1/0):6 \
        with linespoints dt 2 title "megakernel, ".sm
}
