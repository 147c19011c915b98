#!/bin/sh
# check-layers.sh LIB LAYER...: the rules of the core's layout.
#  1. every source and header of src/core sits in a layer folder;
#  2. a file of layer k includes (with "") only headers of layers <= k;
#  3. every header a file includes with "" exists in some layer (or, for a
#     private header, beside the file);
#  4. every global symbol that LIB defines starts with vx_ (but for the
#     weak symbols a C++ compiler emits for what the OpenEXR headers
#     define inline: mangled _Z names and DW.ref.* of exception tables).
# Prints one line per broken rule and exits 1 if any; silent otherwise.
set -u
lib=$1; shift
layers="$*"
bad=0
say() { echo "check-layers: $*" >&2; bad=1; }

rank() {   # rank LAYER: its position in $layers, or empty
	_i=0
	for _l in $layers; do
		[ "$_l" = "$1" ] && { echo $_i; return; }
		_i=$((_i + 1))
	done
}

for f in $(find src/core -name '*.[ch]' -o -name '*.cc' | sort); do
	d=${f#src/core/}
	layer=${d%%/*}
	if [ "$layer" = "$d" ] || [ -z "$(rank "$layer")" ]; then
		say "$f: not in a layer folder ($layers)"
		continue
	fi
	mine=$(rank "$layer")
	for h in $(sed -n 's/^[ \t]*#[ \t]*include[ \t]*"\([^"]*\)".*/\1/p' "$f"); do
		if [ -e "$(dirname "$f")/$h" ]; then
			hl=$layer
		else
			hl=
			for l in $layers; do
				[ -e "src/core/$l/$h" ] && { hl=$l; break; }
			done
		fi
		if [ -z "$hl" ]; then
			say "$f: includes \"$h\", which is in no layer"
		elif [ "$(rank "$hl")" -gt "$mine" ]; then
			say "$f ($layer) includes \"$h\" from the later layer $hl"
		fi
	done
done

if [ -n "$lib" ]; then
	if ! command -v nm >/dev/null 2>&1; then
		echo "check-layers: no nm: exported names not checked" >&2
	else
		# ASan's __odr_asan.NAME marks each exported variable NAME
		nm -g --defined-only "$lib" | awk 'NF == 3 { n = $3; sub(/^__odr_asan\./, "", n)
		    if (n !~ /^vx_/ && !($2 ~ /^[WVu]$/ && n ~ /^(_Z|DW\.ref\.)/)) print $3 }' \
		    | sort -u > "${TMPDIR:-/tmp}/check-layers.$$"
		if [ -s "${TMPDIR:-/tmp}/check-layers.$$" ]; then
			say "$lib exports names without the vx_ prefix: $(tr '\n' ' ' < "${TMPDIR:-/tmp}/check-layers.$$")"
		fi
		rm -f "${TMPDIR:-/tmp}/check-layers.$$"
	fi
fi
exit $bad
