# The calibration of lane confidence over tools/eval_lanes.py --calibration
# lines ("...: confidence 0.50..0.75: N sides seen, M right"): prints the
# sides seen with confidence >= 0.5 and how many were right, and exits 1
# unless at least `floor` of them (awk -v floor=0.95) were.
$2 == "confidence" && $3 >= "0.50" { seen += $4; right += $7 }
END {
    printf "confidence >= 0.5: %d sides seen, %d right (%.1f%%)\n", seen, right,
           seen ? 100 * right / seen : 0
    exit !(seen > 0 && right >= floor * seen)
}
