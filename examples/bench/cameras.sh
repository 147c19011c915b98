# cameras.sh: the benchmark cameras of table (a) as scene lines, for the
# scripts that drive raycast and isobench directly (sourced by pixcheck.sh,
# isoab.sh and corepair.sh; the Makefile gives isobench.py the same views as
# flags)
CAM_CH2="camera perspective eye 295 495 123 look 0 -17 19 up 0 0 1 fov 30"
CAM_VHF="camera perspective eye 560 -480 330 look 260 295 117 up 0 0 1 fov 30"

# embree_flags CAM: a perspective scene line above as embree_render's flags
# (--eye X Y Z --look X Y Z --up X Y Z --fov DEG), the one copy of the numbers
embree_flags() {
	echo "$1" | sed 's/^camera perspective eye /--eye /; s/ look / --look /;
	    s/ up / --up /; s/ fov / --fov /'
}
