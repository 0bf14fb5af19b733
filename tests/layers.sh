#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# layers.sh [ROOT]: checks the #include lines of ROOT/lib and ROOT/tools against the layering
# of lib/ (share/doc/architecture.md, "Layers").  Layers, lowest first:
#     base < pack < contact < analysis < {qs, dem}
# A lib file includes headers of its own layer and of lower ones only (so qs and dem never
# include each other), every one of our includes names its layer ("pack/pack.h"), tools
# include no private header (*_priv.h), and the modules (x.c with x.h) form no include
# circle.  Prints one line per violation and exits 1 when there is any, 0 otherwise.
root=${1:-.}
# rank LAYER: sets r to the layer's rank, -1 for no layer (a variable, not a command
# substitution: a fork per include line made the check take seconds)
rank() {
	case $1 in
	base) r=0 ;; pack) r=1 ;; contact) r=2 ;; analysis) r=3 ;; qs|dem) r=4 ;;
	*) r=-1 ;;
	esac
}
bad=0
edges=$(mktemp) || exit 2
trap 'rm -f "$edges"' EXIT
for f in "$root"/lib/*/*.[ch] "$root"/tools/*.c; do
	[ -f "$f" ] || continue
	rel=${f#"$root"/}
	case $rel in
	lib/*) from=${rel#lib/} from=${from%%/*} ;;
	*) from=tools ;;
	esac
	mod=${rel%.[ch]}
	# quoted includes only: system headers are not ours
	sed -n 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"\([^"]*\)".*/\1/p' "$f" >"$edges.inc"
	while read -r inc; do
		case $inc in
		*/*) to=${inc%%/*} ;;
		*) to= ;;
		esac
		if [ -z "$to" ] || [ ! -f "$root/lib/$inc" ]; then
			echo "$rel: #include \"$inc\" is not a lib header named by its layer"
			bad=1
			continue
		fi
		echo "$mod lib/${inc%.h}" >>"$edges"
		if [ "$from" = tools ]; then
			case $inc in *_priv.h)
				echo "$rel: a tool includes the private header $inc"
				bad=1 ;;
			esac
			continue
		fi
		rank "$from"
		rf=$r
		rank "$to"
		rt=$r
		if [ "$rf" -lt 0 ]; then
			echo "$rel: lib/$from is not a layer"
			bad=1
		elif [ "$from" != "$to" ] && [ "$rt" -ge "$rf" ]; then
			echo "$rel: layer $from must not include $inc (layer $to)"
			bad=1
		fi
	done <"$edges.inc"
	rm -f "$edges.inc"
done
# a module including itself (x.c -> x.h) is no circle; tsort sees a self-edge as none
if ! tsort "$edges" >/dev/null 2>"$edges.err"; then
	sed 's/^/include circle: /' "$edges.err"
	bad=1
fi
rm -f "$edges.err"
exit $bad
