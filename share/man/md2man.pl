#!/usr/bin/perl
# SPDX-License-Identifier: GPL-3.0-or-later
# md2man.pl VERSION < share/doc/tables.md > share/man/man5/qusgm-tables.5
# The manual page of a document of share/doc/, in man(7) macros, so that the document stays
# the one source (qusgm-tables(5) is share/doc/tables.md: make man-tables).  The document
# names its page in comment lines at its top:
#     <!-- man: NAME SECTION -->
#     <!-- man-description: what the NAME line says -->
#     <!-- man-see-also: page(1), page(5) -->
# The rest is the Markdown that those documents use: '#' and '##' headings, paragraphs, '- '
# lists, code blocks indented by four spaces, tables of '| a | b | c |' rows (the first column
# the name, the second its unit, the rest the meaning), `code`, **bold** and [text](target)
# links.
use strict;
use warnings;

my ($version) = @ARGV;
die "usage: md2man.pl VERSION < DOCUMENT > PAGE\n" unless defined $version;
my @lines = <STDIN>;
chomp @lines;
my ($name, $sec, $desc, $seealso);
while (@lines && $lines[0] =~ /^<!-- (man[\w-]*): (.*?) -->$/) {
	my ($k, $v) = ($1, $2);
	($name, $sec) = split ' ', $v if $k eq 'man';
	$desc = $v if $k eq 'man-description';
	$seealso = $v if $k eq 'man-see-also';
	shift @lines;
}
die "md2man.pl: the document has no '<!-- man: NAME SECTION -->' line\n" unless defined $name && defined $sec;
$desc = '' unless defined $desc;

sub esc {
	my $t = shift;
	$t =~ s/\\\|/|/g;		# Markdown's escaped bar in a table cell
	$t =~ s/\\/\\e/g;
	$t =~ s/-/\\-/g;
	$t =~ s/\[([^\]]+)\]\(([^)]+)\)/$1/g;
	$t =~ s/\*\*([^*]+)\*\*/\\fB$1\\fR/g;
	$t =~ s/`([^`]+)`/\\fB$1\\fR/g;
	$t =~ s/^([.'])/\\&$1/;
	$t =~ s/\x{c2}\x{a7}/section /g;	# the section sign, in UTF-8: ASCII for every device
	return $t;
}

my $src = $name; $src =~ s/^qusgm-//;
print ".\\\" Made from share/doc/$src.md by share/man/md2man.pl (make man-tables): edit the .md.\n";
print ".TH " . uc($name) . " $sec \"\" \"qusgm $version\"\n.SH NAME\n$name \\- " . esc($desc) . "\n.SH DESCRIPTION\n";

my ($in_code, $in_list, $need_pp, $first_h1) = (0, 0, 0, 1);
for (my $i = 0; $i < @lines; $i++) {
	my $l = $lines[$i];
	if ($l =~ /^    (.*)$/ && !$in_list) {		# code block
		if (!$in_code) { print ".PP\n.RS 4\n.nf\n"; $in_code = 1; }
		(my $c = $1) =~ s/\t/    /g;
		print esc($c) =~ s/\\fB|\\fR//gr, "\n";
		next;
	}
	if ($in_code) { print ".fi\n.RE\n"; $in_code = 0; $need_pp = 1; }
	if ($l =~ /^\s*$/) { $in_list = 0; $need_pp = 1; next; }
	if ($l =~ /^# (.*)/) { next if $first_h1--; print ".SH ", uc(esc($1)), "\n"; $need_pp = 0; next; }
	if ($l =~ /^##+ (.*)/) { print ".SS ", esc($1), "\n"; $need_pp = 0; next; }
	if ($l =~ /^\|/) {				# a table row
		next if $l =~ /^\|\s*-/;		# the separator
		my @c = map { s/^\s+|\s+$//gr } split /(?<!\\)\|/, $l;
		shift @c;
		next if $i + 1 < @lines && $lines[$i + 1] =~ /^\|\s*-/;	# the header row
		my ($col, $unit, @rest) = @c;
		print ".TP\n\\fB", esc($col) =~ s/\\fB|\\fR//gr, "\\fR", ($unit ne '' ? " [" . esc($unit) . "]" : ""), "\n",
		    esc(join(' | ', @rest)), "\n";
		$need_pp = 1;
		next;
	}
	if ($l =~ /^- (.*)/) { print ".IP \\(bu 2\n", esc($1), "\n"; $in_list = 1; $need_pp = 0; next; }
	if ($in_list && $l =~ /^  (\S.*)/) { print esc($1), "\n"; next; }
	if ($need_pp) { print ".PP\n"; $need_pp = 0; }
	print esc($l =~ s/^\s+//r), "\n";
}
print ".fi\n.RE\n" if $in_code;
print ".SH SEE ALSO\n", join(",\n", map { /^(.*)\((\w+)\)$/ ? "\\fB$1\\fR($2)" : $_ } split /,\s*/, $seealso), "\n"
    if defined $seealso;
