!> core_exact_sum: sums that are exact and independent of the order of the
!> terms and of how they are split among accumulators (the ranks), with
!> cancellation, opposite signs, the largest and the subnormal doubles.
program test_core_exact_sum
  use core_kinds, only: rk, i8
  use core_exact_sum, only: exact_sum_t, exact_value, exact_pack, exact_unpack, EXACT_PACKED
  use check, only: check_true, check_summary
  implicit none
  integer, parameter :: N = 10000
  real(rk) :: x(N), r, plain
  integer :: perm(N), i, j, k, t
  type(exact_sum_t) :: a, b, parts(3)
  integer(i8) :: flat(3 * EXACT_PACKED), total(EXACT_PACKED)
  real(rk) :: forward, backward, shuffled, split

  ! Cancellation: a plain sum gives 0.
  call check_true('1e100 + 1 - 1e100 = 1 exactly', value_of([1.0e100_rk, 1.0_rk, &
      -1.0e100_rk]) == 1.0_rk)
  call check_true('-3.5 + 1.25 = -2.25', value_of([-3.5_rk, 1.25_rk]) == -2.25_rk)
  call check_true('x - x = 0', value_of([0.1_rk, -0.1_rk]) == 0.0_rk)
  call check_true('empty sum = 0', exact_value(exact_sum_t()) == 0.0_rk)
  call check_true('huge - huge + 1 = 1', value_of([huge(1.0_rk), -huge(1.0_rk), 1.0_rk]) &
      == 1.0_rk)
  call check_true('smallest subnormal twice = 2 x it', value_of([2.0_rk**(-1074), &
      2.0_rk**(-1074)]) == 2.0_rk**(-1073))
  call check_true('1 + 2^-53 + 2^-53 = 1 + 2^-52 (a plain sum gives 1)', &
      value_of([1.0_rk, 2.0_rk**(-53), 2.0_rk**(-53)]) == 1.0_rk + 2.0_rk**(-52))

  ! Exact for terms k 2^-20 whose sum an integer holds.
  call random_seed(put=[(4321 + i, i = 1, 64)])
  k = 0
  do i = 1, N
    call random_number(r)
    j = int(2000001.0_rk * r) - 1000000
    x(i) = real(j, rk) * 2.0_rk**(-20)
    k = k + j
  end do
  call check_true('sum of 10^4 multiples of 2^-20 exact', value_of(x) == &
      real(k, rk) * 2.0_rk**(-20))

  ! Order and split independence over mixed magnitudes and signs.
  do t = 1, 3
    do i = 1, N
      call random_number(r)
      x(i) = (r - 0.5_rk) * 2.0_rk**(int(60.0_rk * r) - 30 + 20 * t)
    end do
    forward = value_of(x)
    backward = value_of(x(N:1:-1))
    do i = 1, N
      perm(i) = i
    end do
    do i = N, 2, -1
      call random_number(r)
      j = 1 + int(r * real(i, rk))
      k = perm(i)
      perm(i) = perm(j)
      perm(j) = k
    end do
    shuffled = value_of(x(perm))
    ! Three "ranks": every third term, summed, packed, their limbs added.
    do j = 1, 3
      parts(j) = exact_sum_t()
      do i = j, N, 3
        call parts(j)%add(x(perm(i)))
      end do
    end do
    call exact_pack(parts, flat)
    total = flat(1:EXACT_PACKED) + flat(EXACT_PACKED + 1:2 * EXACT_PACKED) + &
        flat(2 * EXACT_PACKED + 1:)
    call exact_unpack(total, parts(1:1))
    split = exact_value(parts(1))
    plain = sum(x)
    call check_true('same bits forward, backward, shuffled and split in 3', &
        forward == backward .and. forward == shuffled .and. forward == split)
    call check_true('within 1e-12 of the plain sum (a sanity check of the scale)', &
        abs(forward - plain) <= 1.0e-12_rk * sum(abs(x)))
  end do

  ! Accumulating into a copy and adding terms in two halves agree.
  a = exact_sum_t()
  b = exact_sum_t()
  do i = 1, N
    call a%add(x(i))
    if (i <= N / 2) call b%add(x(i))
  end do
  do i = N / 2 + 1, N
    call b%add(x(i))
  end do
  call check_true('one accumulator, added to in two passes', exact_value(a) == exact_value(b))
  call check_summary()

contains

  real(rk) function value_of(v)
    real(rk), intent(in) :: v(:)
    type(exact_sum_t) :: s
    integer :: m
    do m = 1, size(v)
      call s%add(v(m))
    end do
    value_of = exact_value(s)
  end function value_of

end program test_core_exact_sum
