#!/usr/bin/perl
# SPDX-License-Identifier: GPL-3.0-or-later
# citations.pl TOP [FILE...]: every citation in the tree TOP (or in the FILEs only, resolved
# against TOP) resolves (tests/tools/citations.sh runs it).
#
# Citations looked for in lib/, tools/, tests/, share/, bench/, validate/, pipelines/, README.md,
# NEWS and the Makefile (text files; the fuzz corpus and generated outputs left out):
#   - a document: share/doc/X.md, bench/X.md, validate/X.md, pipelines/X.md, or a bare X.md that
#     must then be a file of share/doc/, bench/, validate/, pipelines/ or the top (names of
#     files that a run writes, such as report.md, are allowed by the list below);
#   - a section of a document: 'X.md, "Heading"' needs a heading of X.md containing Heading;
#   - a section of physics.md: 'physics.md §N', '§N-M', '§N, §M', 'section N' needs '## N.';
#   - a paper's equation: 'F (6)', 'F (6)-(7b)', 'S (4)-(5)', 'P eq. 7', 'P eqs. 2-5',
#     'P eq. A2' needs the key in physics.md's index (§14; F (13) is found as F (13a));
#   - a paper's section, figure or appendix: 'F §3.2', 'S section 4.2', 'P §II B', 'F Fig. 4',
#     'F App. A' needs the paper's key in physics.md's reference list.
# Prints one line per citation that does not resolve, "FILE:LINE: what", and exits 1 if any.
use strict;
use warnings;

my $top = shift or die "usage: citations.pl TOP [FILE...]\n";
my @only = map { m{^/} ? $_ : do { require Cwd; Cwd::getcwd() . "/$_" } } @ARGV;
chdir $top or die "citations.pl: $top: $!\n";

# Names of files a run writes (a study's report, a benchmark's result), not documents of the tree.
my %generated = map { $_ => 1 } qw(report.md plates.md);

sub slurp { my $f = shift; open my $h, '<', $f or return undef; local $/; my $s = <$h>; close $h; $s }

my $physics = slurp('share/doc/physics.md');
die "citations.pl: share/doc/physics.md: missing\n" unless defined $physics;
my %psection;
$psection{$1} = 1 while $physics =~ /^## (\d+)\. /mg;
my ($index) = $physics =~ /^## 14\. .*?\n(.*?)(?=^## )/ms;
die "citations.pl: share/doc/physics.md: no section 14 (the index of the papers' equations)\n" unless $index;
my ($refs) = $physics =~ /^## References\n(.*?)(?=^## )/ms;
die "citations.pl: share/doc/physics.md: no reference list\n" unless $refs;
my %paperkey;
$paperkey{$1} = 1 while $refs =~ /^- \*\*([A-Z]+)\*\*/mg;

# The index's keys: F (7b), S (4), P eq. 7; P eqs. 15-17 and P eqs. A3-A5 give each number.
my %eq;
for my $row (split /\n/, $index) {
	next unless $row =~ /^\| ([^|]+) \|/;
	my $k = $1;
	$eq{"$1 ($2)"} = 1 while $k =~ /\b([FS]) \((A?\d+[a-z]?)\)/g;
	while ($k =~ /\bP eqs?\. (A?)(\d+)(?:-A?(\d+))?/g) {
		my ($a, $lo, $hi) = ($1, $2, defined $3 ? $3 : $2);
		$eq{"P $a$_"} = 1 for $lo .. $hi;
	}
}

sub eq_known {
	my ($paper, $n) = @_;
	return $eq{"P $n"} if $paper eq 'P';
	return 1 if $eq{"$paper ($n)"};
	return $n =~ /^\d+$/ && ($eq{"$paper (${n}a)"} || $eq{"$paper (${n}b)"});
}

# the tree's own files: what git tracks (and untracked files it does not ignore) in a
# checkout, else (a tarball) every file but the outputs of tests and studies, which other
# tests write while this one runs
my @files = -d ".git" ? split(/\n/, `git ls-files --cached --others --exclude-standard 2>/dev/null`) : ();
@files = split /\n/, `find lib tools tests share bench validate pipelines -type f 2>/dev/null` unless @files;
push @files, grep { -f } qw(README.md NEWS Makefile);
my %seen;
@files = sort grep { !$seen{$_}++ && -f && !m{^tests/(fuzz/corpus|out)/} && !m{^pipelines/out[^/]*/} &&
    m{^(lib|tools|tests|share|bench|validate|pipelines)/|^(README\.md|NEWS|Makefile)$} && !m{\.(png|gz|o|a|so)$} && -T } @files;
@files = @only if @only;

my $bad = 0;
sub bad { my ($f, $l, $what) = @_; print "$f:$l: $what\n"; $bad++ }

# The file a citation of document D in file F means: D itself when it names a folder, else
# D in F's folder, share/doc/, bench/, validate/, pipelines/ or the top, the first found.
sub doc_path {
	my ($f, $d) = @_;
	return -f $d ? $d : undef if $d =~ m{/};
	(my $dir = $f) =~ s{/?[^/]*$}{};
	my ($path) = grep { -f } map { ($_ eq '' ? '' : "$_/") . $d } ($dir, qw(share/doc bench validate pipelines), '');
	return $path;
}

for my $f (@files) {
	next if $f eq 'tests/citations.pl' || $f eq 'tests/tools/citations.sh';
	open my $h, '<', $f or next;
	my $ln = 0;
	while (my $line = <$h>) {
		$ln++;
		$line =~ s/\\\(sc/§/g;	# roff's section sign
		$line =~ s/\\-/-/g;	# roff's hyphen
		# documents of the tree, by path or by name
		while ($line =~ m{(?<![\w./-])((?:(?:share/doc|bench|validate|pipelines)/)?[A-Za-z0-9_-]+\.md)\b}g) {
			my $d = $1;
			my $before = substr($line, 0, $-[1]);
			next if $before =~ m{(?:\$\w*|\w|\)|/)$};	# a path below a variable or another folder
			bad($f, $ln, "cites $d, which is not in the tree") unless $generated{$d} || doc_path($f, $d);
		}
		# nothing outside the tree
		bad($f, $ln, "cites $1, outside the tree") while $line =~ m{((?:\.\./)+shared/\S*|/work/shared\S*)}g;
		# a document's section by its heading
		# (a heading line, or a paragraph that opens with it in bold)
		while ($line =~ m{((?:[\w-]+/)*[\w-]+\.md),? "([^"]+)"}g) {
			my ($d, $sec) = ($1, $2);
			my $path = doc_path($f, $d) or next;
			my $text = slurp($path);
			bad($f, $ln, "cites $d, \"$sec\", a heading $path does not have")
			    unless $text =~ /^#+ .*\Q$sec\E/m || $text =~ /^\*\*\Q$sec\E/m;
		}
		# sections of physics.md
		while ($line =~ /physics\.md,? (?:§ ?|sections? )(\d+(?:\s*(?:-|,|and)\s*(?:§)?\s*\d+)*)/g) {
			my $list = $1;
			for my $part (split /\s*(?:,|and)\s*/, $list) {
				$part =~ s/§\s*//g;
				my ($lo, $hi) = $part =~ /^(\d+)(?:\s*-\s*(\d+))?$/ or next;
				$hi = $lo unless defined $hi;
				for my $n ($lo .. $hi) {
					bad($f, $ln, "cites physics.md §$n, which physics.md does not have") unless $psection{$n};
				}
			}
		}
		# the papers' equations
		while ($line =~ /\b([FS]) \((A?\d+[a-z]?)\)(?:\s*-\s*\((A?\d+[a-z]?)\))?/g) {
			for my $n (grep { defined } ($2, $3)) {
				bad($f, $ln, "cites $1 ($n), which physics.md's index (§14) does not list") unless eq_known($1, $n);
			}
		}
		while ($line =~ /\bP eqs?\. ?(A?)(\d+)(?:\s*(?:-|and|,)\s*A?(\d+))?/g) {
			my ($a, $lo, $hi) = ($1, $2, defined $3 ? $3 : $2);
			for my $n ($lo .. $hi) {
				bad($f, $ln, "cites P eq. $a$n, which physics.md's index (§14) does not list") unless eq_known('P', "$a$n");
			}
		}
		# the papers' sections, figures, appendices: the key must be defined
		while ($line =~ /(?<![\w.])([A-Z]) §|\b([FSP]) (?:section \d|App\.|Appendix [A-Z]|Figs?\. ?\d)/g) {
			my $k = defined $1 ? $1 : $2;
			bad($f, $ln, "cites paper $k, which physics.md's reference list does not define") unless $paperkey{$k};
		}
	}
	close $h;
}
exit($bad ? 1 : 0);
