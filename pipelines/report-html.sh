#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# report-html.sh STUDY DIR: DIR/report.md as a page to open in a browser, on standard output:
# its text and tables, the study's figure DIR/STUDY.png and the picture of its pack
# (pack.png), and a link to the 3D view of the pack, DIR/pack.html (packview), each when
# there.  Only what report.sh writes is read: headings, paragraphs, **bold**, `code`,
# images and tables.  The files are linked by their names, so that DIR moves as one.
set -e
study=$1 dir=$2
fig=""
[ -f "$dir/$study.png" ] && fig="$study.png"
view=""
[ -f "$dir/pack.html" ] && view=pack.html
awk -v study="$study" -v fig="$fig" -v view="$view" '
function esc(s) {
	gsub(/&/, "\\&amp;", s)
	gsub(/</, "\\&lt;", s)
	gsub(/>/, "\\&gt;", s)
	return s
}
# inline markup: images, `code`, **bold**
function inline(s,    out, m, alt, src) {
	s = esc(s)
	while (match(s, /!\[[^]]*\]\([^)]*\)/)) {
		m = substr(s, RSTART, RLENGTH)
		alt = m; sub(/^!\[/, "", alt); sub(/\].*$/, "", alt)
		src = m; sub(/^[^(]*\(/, "", src); sub(/\)$/, "", src)
		s = substr(s, 1, RSTART - 1) "<img alt=\"" alt "\" src=\"" src "\">" substr(s, RSTART + RLENGTH)
	}
	while (match(s, /`[^`]*`/))
		s = substr(s, 1, RSTART - 1) "<code>" substr(s, RSTART + 1, RLENGTH - 2) "</code>" substr(s, RSTART + RLENGTH)
	while (match(s, /\*\*[^*]*\*\*/))
		s = substr(s, 1, RSTART - 1) "<b>" substr(s, RSTART + 2, RLENGTH - 4) "</b>" substr(s, RSTART + RLENGTH)
	return s
}
function close_block() {
	if (para) print "</p>"
	if (table) print "</table>"
	para = table = 0
}
function cells(s, tag,    n, a, k, row) {
	sub(/^\| */, "", s); sub(/ *\|$/, "", s)
	n = split(s, a, / *\| */)
	row = "<tr>"
	for (k = 1; k <= n; k++)
		row = row "<" tag ">" inline(a[k]) "</" tag ">"
	return row "</tr>"
}
BEGIN {
	print "<!DOCTYPE html>"
	print "<html lang=\"en\"><head><meta charset=\"utf-8\"><title>qusgm study " esc(study) "</title>"
	print "<style>body { font: 15px/1.45 sans-serif; max-width: 60em; margin: 1em auto; padding: 0 1em; }"
	print "table { border-collapse: collapse; margin: 0.6em 0; } td, th { border: 1px solid #bbb; padding: 2px 6px; }"
	print "th { background: #eee; } img { max-width: 100%; } code { background: #f2f2f2; }"
	print ".view { font-size: 17px; margin: 0.8em 0; }</style></head><body>"
}
/^#+ / {
	close_block()
	h = match($0, /[^#]/) - 1
	t = substr($0, h + 2)
	print "<h" h ">" inline(t) "</h" h ">"
	if (h == 1) {
		if (view != "")
			print "<p class=\"view\"><a href=\"" view "\">The pack of this study in 3D</a> (packview: grains, force chains, slabs; opens offline)</p>"
		if (fig != "")
			print "<p><img alt=\"the study&#39;s figure\" src=\"" fig "\"></p>"
	}
	next
}
/^\|/ {
	if (para) { print "</p>"; para = 0 }
	if ($0 ~ /^\|( *-+ *\|)+ *$/)
		next
	if (!table) { print "<table>"; table = 1; print cells($0, "th"); next }
	print cells($0, "td")
	next
}
/^[ \t]*$/ { close_block(); next }
{
	if (table) { print "</table>"; table = 0 }
	if (!para) { printf "<p>"; para = 1 }
	print inline($0)
}
END {
	close_block()
	print "</body></html>"
}' "$dir/report.md"
