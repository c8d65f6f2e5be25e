#!/usr/bin/perl
# A stand-in for mimic in the scripts' tests (perl-base only, which every Debian has): appends each
# call (event, -o, arguments) to $FAKE_LOG, in the order they happen; "trains" for $FAKE_SECONDS
# (twice that for a run named *humanoid_walk), then writes -o's model as mimic imitate does.
# SIGINT makes it log "stopped" and exit 130, as mimic does after saving, even where the signal was
# ignored when it started. A run whose arguments contain $FAKE_FAIL (where set) logs "failed" and
# exits 4 at once; one started --from runs/zoo/humanoid_walk/model before that model exists, 3.
# `play` writes its --motion (empty) and --json: a "recovered" event at each of $FAKE_RECOVERED's
# times.
use strict;
use warnings;
use File::Path qw(make_path);

my @args = @ARGV;
my $out = '-';
for my $i (0 .. $#args - 1) { $out = $args[$i + 1] if $args[$i] eq '-o'; }

sub note {
  open(my $log, '>>', $ENV{FAKE_LOG}) or die "fake_mimic: $ENV{FAKE_LOG}: $!";
  print $log "$_[0] $out @args\n";
  close($log);
}

sub touch {
  open(my $f, '>', $_[0]) or die "fake_mimic: $_[0]: $!";
  close($f);
}

# The value after option $_[0] in the arguments, or undef.
sub option {
  for my $i (0 .. $#args - 1) { return $args[$i + 1] if $args[$i] eq $_[0]; }
  return undef;
}

note('start');
$SIG{INT} = sub { note('stopped'); exit 130; };
if ($args[0] eq 'play') {  # a session: its motion, and its events with $FAKE_RECOVERED's hand-backs
  touch(option('--motion')) if defined option('--motion');
  if (defined option('--json')) {
    open(my $f, '>', option('--json')) or die "fake_mimic: " . option('--json') . ": $!";
    my @events = map { qq(  {"t": $_, "event": "recovered", "skill": "walk"}) } split(' ', $ENV{FAKE_RECOVERED} // '');
    print $f "[\n" . join(",\n", @events) . "\n]\n";
    close($f);
  }
  exit 0;
}
if ($args[0] eq 'demo') {
  make_path($out);
  touch("$out/jumping_jack.mclip");
  exit 0;
}
if (grep({ $_ eq 'runs/zoo/humanoid_walk/model' } @args) && !-f 'runs/zoo/humanoid_walk/model/networks.mimic') {
  note('failed');
  exit 3;
}
if ($ENV{FAKE_FAIL} && "@args" =~ /\Q$ENV{FAKE_FAIL}\E/) {
  note('failed');
  exit 4;
}
my $seconds = $ENV{FAKE_SECONDS} // 1;
$seconds *= 2 if $out =~ /humanoid_walk$/;
select(undef, undef, undef, $seconds);  # a sleep (SIGINT ends it)
my $model = $args[0] eq 'export' ? $out : "$out/model";
make_path($model);
touch("$model/networks.mimic");
if ($args[0] eq 'imitate') { touch("$out/$_") for ('eval.json', 'report.md', 'curves.png', 'video.mp4'); }
note('done');
