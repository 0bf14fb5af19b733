# SPDX-License-Identifier: GPL-3.0-or-later
# makerun: make run's script (share/run-default.sh) on a 200-grain pack, its tools from a
# directory whose name has a space in it; every command it prints ("== STAGE: COMMAND") is
# then pasted into a shell as it is, in another directory, and makes the same files.  Issue 59:
# the loadtest and probe stages printed "sh -c 'build/bin/loadtest' --path ...", which ran
# loadtest with no argument when pasted.
. "$TOP/tests/tools/lib.sh"

# the optimised build only: the chain's tools are tested one by one under the sanitizers
if [ "${BIN#*build-san}" != "$BIN" ]; then
	echo "SKIP makerun (left to the optimised build)"
	exit 0
fi
# a scratch directory used before (run.sh --one keeps it) starts empty: ln -s into an existing
# link to a directory would write into the tree
rm -rf "tools dir" a b cmds a.* b.*
ln -s "$BIN" "tools dir"
mkdir a b b/out
ln -s "$TOP/share" a/share	# the figures' scripts, where make run finds them
if (cd a && sh "$TOP/share/run-default.sh" "$PWD/../tools dir" 200 >run.out 2>run.err); then
	pass "run-default.sh on 200 grains"
else
	fail "run-default.sh on 200 grains" "$(tail -n 3 a/run.err)"
fi
sed -n 's/^== [a-z]*: //p' a/run.err >cmds
expect_num "stages printed" "$(grep -c '' cmds)" == 7
if grep -q 'sh -c' cmds; then fail "no stage printed as sh -c" "$(grep 'sh -c' cmds | head -n 1)"; else pass "no stage printed as sh -c"; fi
bad=
while IFS= read -r c; do
	(cd b && sh -c "$c") >/dev/null 2>>b/err || bad="$bad [$c]"
done <cmds
if [ -z "$bad" ]; then pass "every printed command runs pasted"; else fail "every printed command runs pasted" "$bad: $(tail -n 2 b/err)"; fi
same=yes
for f in loose dense frictional final; do
	gzip -dc "a/out/$f.pack.gz" >"a.$f" 2>/dev/null
	gzip -dc "b/out/$f.pack.gz" >"b.$f" 2>/dev/null
	[ -s "a.$f" ] && cmp -s "a.$f" "b.$f" || same="$same $f.pack.gz"
done
for f in curve.tsv moduli.tsv probe.tsv pack.html; do
	[ -s "a/out/$f" ] && cmp -s "a/out/$f" "b/out/$f" || same="$same $f"
done
if [ "$same" = yes ]; then pass "the pasted commands make the same packs and tables"; else fail "the pasted commands make the same packs and tables" "differ or missing:${same#yes}"; fi
