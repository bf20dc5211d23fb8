!> Recursive coordinate bisection: the cut tree is bitwise the same for four
!> distributions of the points over the ranks (round robin, reversed blocks,
!> all on the first rank, all on the last rank), the parts are balanced, and
!> rcb_parts_of_box returns exactly the parts whose region meets a box. Rank 0
!> prints every cut ("tree" lines) so that runs on 1..4 ranks can be diffed.
program test_parallel_rcb
  use, intrinsic :: iso_fortran_env, only: output_unit
  use core_kinds, only: rk, i8
  use parallel_env, only: par_init, par_finalize, par_rank, par_size, par_min
  use parallel_rcb, only: rcb_t, rcb_build, rcb_part_of, rcb_parts_of_box
  use check, only: check_true, check_summary
  implicit none
  integer, parameter :: NPOINT = 2000
  integer, parameter :: NPARTS_LIST(6) = [1, 2, 3, 4, 5, 7]
  integer, parameter :: ROUND_ROBIN = 1, REVERSED_BLOCKS = 2, ON_FIRST = 3, ON_LAST = 4
  real(rk), allocatable :: x(:, :), few(:, :)
  integer(i8), allocatable :: weight(:), gid(:), few_gid(:)
  integer :: m, i

  call par_init()
  call make_points(NPOINT, x, weight, gid)
  do m = 1, size(NPARTS_LIST)
    call check_case('weighted', x, weight, gid, NPARTS_LIST(m), .true.)
  end do
  do m = 1, size(NPARTS_LIST)
    call check_case('unit', x, spread(1_i8, 1, NPOINT), gid, NPARTS_LIST(m), .false.)
  end do
  call check_case('zero weights', x, spread(0_i8, 1, NPOINT), gid, 5, .false.)

  ! Fewer points than parts, no points at all, and a cut on signed zeros.
  call check_case('three points', x(:, 1:3), weight(1:3) + 1, gid(1:3), 7, .true.)
  allocate(few(3, 0), few_gid(0))
  call check_case('no points', few, few_gid, few_gid, 5, .true.)
  deallocate(few, few_gid)
  allocate(few(3, 8), few_gid(8))
  few = 0.0_rk
  do i = 1, 8, 2
    few(1, i) = sign(0.0_rk, -1.0_rk)
  end do
  few_gid = [(int(i, i8), i = 1, 8)]
  call check_case('signed zeros', few, spread(1_i8, 1, 8), few_gid, 3, .true.)

  call par_finalize()
  call check_summary()

contains

  !> A jittered 13 x 13 x 12 lattice: many equal coordinates, repeated points,
  !> signed zeros, weights 0..5 and scrambled global ids 1..n.
  subroutine make_points(n, x, weight, gid)
    integer, intent(in) :: n
    real(rk), allocatable, intent(out) :: x(:, :)
    integer(i8), allocatable, intent(out) :: weight(:), gid(:)
    integer :: i, j
    integer(i8) :: h

    allocate(x(3, n), weight(n), gid(n))
    do i = 1, n
      j = i - 1
      h = mod(7919_i8 * i + 13_i8 * i * i, 10007_i8)
      x(1, i) = -0.6_rk + 0.1_rk * mod(j, 13) + 0.05_rk * mod(h, 2_i8)
      x(2, i) = 0.07_rk * mod(j / 13, 13) + 0.035_rk * mod(h / 2, 2_i8)
      x(3, i) = 0.05_rk * (j / 169) + 0.025_rk * mod(h / 4, 3_i8)
      weight(i) = mod(h / 12, 6_i8)
      ! 1237 is prime to 2000: a permutation of 1..n for n = 2000.
      gid(i) = 1 + mod(1237_i8 * i, int(n, i8))
    end do
    do i = 50, n, 50
      x(:, i) = x(:, i - 1)
    end do
    do i = 37, n, 37
      x(:, i) = x(:, 1)
    end do
    do i = 101, n, 101
      x(2, i) = sign(0.0_rk, -1.0_rk)
    end do
    do i = 103, n, 103
      x(2, i) = 0.0_rk
    end do
  end subroutine make_points

  !> Build for every distribution and check everything for one point set.
  subroutine check_case(label, x, weight, gid, nparts, verbose)
    character(len=*), intent(in) :: label
    real(rk), intent(in) :: x(:, :)
    integer(i8), intent(in) :: weight(:), gid(:)
    integer, intent(in) :: nparts
    logical, intent(in) :: verbose !< print the tree on rank 0
    type(rcb_t) :: tree(4)
    character(len=64) :: name
    integer, allocatable :: part(:), part_other(:)
    integer(i8), allocatable :: part_weight(:), part_count(:)
    integer :: n, i, k, p
    logical :: ok

    write(name, '(a,a,i0)') label, ' nparts=', nparts
    n = size(x, 2)
    do k = 1, 4
      call build(k, x, weight, gid, nparts, tree(k))
    end do
    ok = .true.
    do k = 2, 4
      ok = ok .and. same_tree(tree(1), tree(k))
    end do
    call check_true(trim(name)//': same cut tree for four distributions', all_ranks(ok))

    ! The part of every point, from two of the builds.
    allocate(part(n), part_other(n))
    do i = 1, n
      part(i) = rcb_part_of(tree(1), x(:, i), gid(i))
      part_other(i) = rcb_part_of(tree(2), x(:, i), gid(i))
    end do
    call check_true(trim(name)//': same part of every point for two builds', &
        all_ranks(all(part == part_other)))
    call check_true(trim(name)//': parts in 0..nparts-1', &
        all_ranks(all(part >= 0 .and. part < nparts)))

    ! The build's own weights and counts are those of rcb_part_of.
    allocate(part_weight(0:nparts - 1), part_count(0:nparts - 1))
    part_weight = 0
    part_count = 0
    do i = 1, n
      part_weight(part(i)) = part_weight(part(i)) + weight(i)
      part_count(part(i)) = part_count(part(i)) + 1
    end do
    call check_true(trim(name)//': part weights and counts as built', &
        all_ranks(all(part_weight == tree(1)%part_weight) .and. &
        all(part_count == tree(1)%part_count)))

    ! Every point is in its part's (closed) region; regions are not empty.
    ok = all(tree(1)%part_lo <= tree(1)%part_hi)
    do i = 1, n
      p = part(i)
      ok = ok .and. all(tree(1)%part_lo(:, p) <= x(:, i) .and. x(:, i) <= tree(1)%part_hi(:, p))
    end do
    call check_true(trim(name)//': every point in its region', all_ranks(ok))

    call check_balance(name, tree(1), part_weight, part_count, maxval([0_i8, weight]), &
        all(weight == 1))
    call check_boxes(name, tree(1), x, gid, part)
    if (verbose .and. par_rank() == 0) call print_tree(name, tree(1))
  end subroutine check_case

  !> Build on this rank's share of the points of one distribution.
  subroutine build(distribution, x, weight, gid, nparts, rcb)
    integer, intent(in) :: distribution
    real(rk), intent(in) :: x(:, :)
    integer(i8), intent(in) :: weight(:), gid(:)
    integer, intent(in) :: nparts
    type(rcb_t), intent(out) :: rcb
    integer :: mine(size(x, 2))
    integer :: n, nrank, rank, block, i, first, last, nmine

    n = size(x, 2)
    nrank = par_size()
    rank = par_rank()
    nmine = 0
    select case (distribution)
    case (ROUND_ROBIN)
      do i = rank + 1, n, nrank
        nmine = nmine + 1
        mine(nmine) = i
      end do
    case (REVERSED_BLOCKS)
      ! Rank r holds block nrank - 1 - r, in reversed order.
      block = nrank - 1 - rank
      first = (block * n) / nrank + 1
      last = ((block + 1) * n) / nrank
      do i = last, first, -1
        nmine = nmine + 1
        mine(nmine) = i
      end do
    case (ON_FIRST, ON_LAST)
      if ((distribution == ON_FIRST .and. rank == 0) .or. &
          (distribution == ON_LAST .and. rank == nrank - 1)) then
        nmine = n
        mine = [(i, i = 1, n)]
      end if
    end select
    call rcb_build(x(:, mine(1:nmine)), weight(mine(1:nmine)), gid(mine(1:nmine)), nparts, rcb)
  end subroutine build

  !> Balance, node by node (exact by construction) and part by part.
  subroutine check_balance(name, rcb, part_weight, part_count, max_weight, unit)
    character(len=*), intent(in) :: name
    type(rcb_t), intent(in) :: rcb
    integer(i8), intent(in) :: part_weight(0:), part_count(0:)
    integer(i8), intent(in) :: max_weight !< largest single weight
    logical, intent(in) :: unit !< all weights are 1
    integer(i8) :: node_weight, left_weight, goal, total
    integer :: c, first, last, np, nl, p
    logical :: ok
    real(rk) :: deviation

    ! Left side: the smallest key reaching the target T, so T <= left < T + max_weight.
    ok = .true.
    do c = 1, rcb%nparts - 1
      first = rcb%node_parts(1, c)
      last = rcb%node_parts(2, c)
      np = last - first + 1
      nl = np / 2
      node_weight = sum(part_weight(first:last))
      left_weight = sum(part_weight(first:first + nl - 1))
      if (node_weight == 0) then
        node_weight = sum(part_count(first:last))
        left_weight = sum(part_count(first:first + nl - 1))
      end if
      goal = (2 * node_weight * nl + np) / (2 * np)
      if (unit .or. max_weight == 0) then
        ok = ok .and. left_weight == goal
      else
        ok = ok .and. goal <= left_weight .and. left_weight - goal < max(max_weight, 1_i8)
      end if
    end do
    call check_true(trim(name)//': every cut at its target', all_ranks(ok))

    ! Part by part: within 1 of the ideal share for unit weights, and a loose
    ! 3 max_weight otherwise (the per-cut errors add up along the tree).
    total = sum(part_weight)
    if (total == 0) return
    deviation = 0.0_rk
    do p = 0, rcb%nparts - 1
      deviation = max(deviation, abs(real(part_weight(p), rk) - real(total, rk) / rcb%nparts))
    end do
    if (par_rank() == 0) write(output_unit, '(a,es10.3)') trim(name)//': largest deviation '// &
        'from the ideal part weight ', deviation
    if (unit) then
      ok = all(abs(rcb%nparts * part_weight - total) <= rcb%nparts)
      call check_true(trim(name)//': unit weights within 1 of the ideal share', all_ranks(ok))
    else
      ok = deviation <= 3 * max_weight
      call check_true(trim(name)//': part weights within 3 max weights of the ideal', &
          all_ranks(ok))
    end if
  end subroutine check_balance

  !> Random boxes return exactly the parts whose region meets them (which
  !> includes the part of every point inside); a point box strictly inside a
  !> region returns that part alone.
  subroutine check_boxes(name, rcb, x, gid, part)
    character(len=*), intent(in) :: name
    type(rcb_t), intent(in) :: rcb
    real(rk), intent(in) :: x(:, :)
    integer(i8), intent(in) :: gid(:)
    integer, intent(in) :: part(:)
    integer, parameter :: NBOX = 300
    real(rk) :: lo(3), hi(3)
    integer :: parts(rcb%nparts), expected(rcb%nparts), n, nexpected, b, i, p, d, ninside
    integer(i8) :: seed
    logical :: ok, member(0:rcb%nparts - 1), inside

    seed = 12345
    ok = .true.
    do b = 1, NBOX
      if (mod(b, 3) == 0 .and. size(x, 2) > 0) then
        ! A point box on a random point: often on a cut plane.
        i = 1 + int(uniform(seed) * size(x, 2))
        lo = x(:, i)
        hi = lo
      else
        do d = 1, 3
          lo(d) = -0.7_rk + 1.6_rk * uniform(seed)
          hi(d) = lo(d) + 0.4_rk * uniform(seed)
        end do
      end if
      call rcb_parts_of_box(rcb, lo, hi, parts, n)
      nexpected = 0
      do p = 0, rcb%nparts - 1
        if (all(rcb%part_lo(:, p) <= hi .and. lo <= rcb%part_hi(:, p))) then
          nexpected = nexpected + 1
          expected(nexpected) = p
        end if
      end do
      if (n /= nexpected) then
        ok = .false.
        cycle
      end if
      ok = ok .and. all(parts(1:n) == expected(1:n))
      member = .false.
      member(parts(1:n)) = .true.
      do i = 1, size(x, 2)
        if (all(lo <= x(:, i) .and. x(:, i) <= hi)) ok = ok .and. member(part(i))
      end do
    end do
    call check_true(trim(name)//': parts of random boxes are the regions met', all_ranks(ok))

    ok = .true.
    ninside = 0
    do i = 1, size(x, 2)
      p = part(i)
      call rcb_parts_of_box(rcb, x(:, i), x(:, i), parts, n)
      inside = all(rcb%part_lo(:, p) < x(:, i) .and. x(:, i) < rcb%part_hi(:, p))
      if (inside) then
        ninside = ninside + 1
        ok = ok .and. n == 1
        if (n == 1) ok = ok .and. parts(1) == p
      else
        ok = ok .and. n >= 1 .and. any(parts(1:min(n, size(parts))) == p)
      end if
      ok = ok .and. rcb_part_of(rcb, x(:, i), gid(i)) == p
    end do
    call check_true(trim(name)//': a point box returns its own part (alone if inside)', &
        all_ranks(ok .and. (ninside > 0 .or. size(x, 2) < 100)))
  end subroutine check_boxes

  !> Every cut, bitwise (es25.16e3), for diffing runs on different rank counts.
  subroutine print_tree(name, rcb)
    character(len=*), intent(in) :: name
    type(rcb_t), intent(in) :: rcb
    integer :: c, p

    write(output_unit, '(a,a,i0)') 'tree ', trim(name)//' reductions ', rcb%reductions
    do c = 1, rcb%nparts - 1
      write(output_unit, '(a,a,i0,a,i0,a,es25.16e3,a,i0,a,i0,1x,i0,a,i0,1x,i0)') 'tree ', &
          trim(name)//' node ', c, ' dim ', rcb%cut_dim(c), ' value ', rcb%cut_value(c), &
          ' gid ', rcb%cut_gid(c), ' children ', rcb%child(:, c), ' parts ', rcb%node_parts(:, c)
    end do
    do p = 0, rcb%nparts - 1
      write(output_unit, '(a,a,i0,a,i0,a,i0,a,3es25.16e3,a,3es25.16e3)') 'tree ', trim(name)// &
          ' part ', p, ' weight ', rcb%part_weight(p), ' count ', rcb%part_count(p), &
          ' lo', rcb%part_lo(:, p), ' hi', rcb%part_hi(:, p)
    end do
  end subroutine print_tree

  !> Every component equal, reals compared bitwise.
  logical function same_tree(a, b)
    type(rcb_t), intent(in) :: a, b

    same_tree = a%nparts == b%nparts .and. a%reductions == b%reductions
    if (.not. same_tree) return
    same_tree = all(a%cut_dim == b%cut_dim) .and. all(a%cut_gid == b%cut_gid) .and. &
        all(bits(a%cut_value) == bits(b%cut_value)) .and. all(a%child == b%child) .and. &
        all(a%node_parts == b%node_parts) .and. &
        all(bits(reshape(a%part_lo, [size(a%part_lo)])) == &
        bits(reshape(b%part_lo, [size(b%part_lo)]))) .and. &
        all(bits(reshape(a%part_hi, [size(a%part_hi)])) == &
        bits(reshape(b%part_hi, [size(b%part_hi)]))) .and. &
        all(a%part_weight == b%part_weight) .and. all(a%part_count == b%part_count)
  end function same_tree

  !> The bit patterns of reals.
  function bits(v) result(b)
    real(rk), intent(in) :: v(:)
    integer(i8) :: b(size(v))
    b = transfer(v, 0_i8, size(v))
  end function bits

  !> True when the condition holds on every rank.
  logical function all_ranks(condition)
    logical, intent(in) :: condition
    all_ranks = par_min(merge(1, 0, condition)) == 1
  end function all_ranks

  !> Park-Miller minimal standard generator, uniform in [0, 1).
  real(rk) function uniform(seed)
    integer(i8), intent(inout) :: seed
    seed = mod(16807_i8 * seed, 2147483647_i8)
    uniform = real(seed - 1, rk) / 2147483647.0_rk
  end function uniform

end program test_parallel_rcb
