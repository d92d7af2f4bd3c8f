## -*- texinfo -*-
## @deftypefn {} {} pathzoo_seed (@var{seed})
## Seed every random generator of Octave (rand, randi, randperm, randn, rande, randg, randp) from @var{seed}.
## @end deftypefn

function pathzoo_seed (seed)
  rand ("state", seed);
  randn ("state", seed);
  rande ("state", seed);
  randg ("state", seed);
  randp ("state", seed);
endfunction
