# cameras.sh: the benchmark cameras of table (a) as scene lines, for the
# scripts that drive raycast and isobench directly (sourced by pixcheck.sh
# and isoab.sh; the Makefile gives isobench.py the same views as flags)
CAM_CH2="camera perspective eye 295 495 123 look 0 -17 19 up 0 0 1 fov 30"
CAM_VHF="camera perspective eye 560 -480 330 look 260 295 117 up 0 0 1 fov 30"
