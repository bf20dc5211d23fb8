!> Exact sums of reals, independent of the order of their terms.
!>
!> Every finite double is an integer multiple of 2^-1074; an exact_sum_t
!> holds the sum of its terms as a fixed-point integer of that unit, in limbs
!> of 32 bits kept in 64-bit integers (headroom for 2^30 additions between
!> carry propagations). Integer addition is associative, so the accumulated
!> integer, and the double made from it, do not depend on the order of the
!> terms, on how they were split among ranks, or on the rank count: the
!> reduction over ranks (par_sum_exact in parallel_env) adds normalised limbs
!> as integers. The value is the exact sum rounded to a double (within one
!> ulp of the correctly rounded sum, always the same for the same integer).
!> Used for the history's global sums, which are then bitwise identical on
!> any rank count and across restarts.
module core_exact_sum
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use core_kinds, only: rk, i8
  implicit none
  private
  public :: exact_value, exact_pack, exact_unpack, exact_add_all, exact_add_each, exact_merge

  !> Limbs: bit 0 of limb 0 is 2^-1126 (below the smallest subnormal's
  !> mantissa once shifted), the largest double's top bit lands in limb 67,
  !> the rest is room for carries.
  integer, parameter, public :: EXACT_LIMBS = 72
  integer, parameter :: BIAS = 1126
  integer(i8), parameter :: MASK32 = 4294967295_i8
  integer, parameter :: NORMALISE_EVERY = 2**30

  !> An exact sum (start: a default-initialised value is 0).
  type, public :: exact_sum_t
    integer(i8) :: limb(0:EXACT_LIMBS - 1) = 0_i8
    integer(i8) :: nonfinite = 0_i8 !< terms that were Inf or NaN (the value is then NaN)
    integer :: adds = 0 !< additions since the last carry propagation
  contains
    procedure :: add => exact_add
    procedure :: normalise => exact_normalise
  end type exact_sum_t

  !> Values per packed exact sum (limbs and the non-finite count).
  integer, parameter, public :: EXACT_PACKED = EXACT_LIMBS + 1

contains

  !> acc = acc + x, exactly.
  subroutine exact_add(acc, x)
    class(exact_sum_t), intent(inout) :: acc
    real(rk), intent(in) :: x
    call deposit(acc%limb, acc%nonfinite, x)
    acc%adds = acc%adds + 1
    if (acc%adds >= NORMALISE_EVERY) call acc%normalise()
  end subroutine exact_add

  !> acc = acc + sum(x), exactly (one call for many terms: the history's
  !> sums over zones and nodes).
  subroutine exact_add_all(acc, x)
    type(exact_sum_t), intent(inout) :: acc
    real(rk), intent(in) :: x(:)
    integer :: i, first, last
    ! In runs that leave the limbs room for the carries.
    do first = 1, size(x), NORMALISE_EVERY
      last = min(size(x), first + NORMALISE_EVERY - 1)
      if (acc%adds > NORMALISE_EVERY - (last - first + 1)) call acc%normalise()
      do i = first, last
        call deposit(acc%limb, acc%nonfinite, x(i))
      end do
      acc%adds = acc%adds + (last - first + 1)
    end do
  end subroutine exact_add_all

  !> acc = acc + other, exactly (the sum of both sums' terms).
  subroutine exact_merge(acc, other)
    type(exact_sum_t), intent(inout) :: acc
    type(exact_sum_t), intent(in) :: other
    type(exact_sum_t) :: b
    b = other
    call b%normalise()
    call acc%normalise()
    acc%limb = acc%limb + b%limb
    acc%nonfinite = acc%nonfinite + b%nonfinite
    acc%adds = 1
  end subroutine exact_merge

  !> accs(which(i)) = accs(which(i)) + x(i) for every i, exactly.
  subroutine exact_add_each(accs, which, x)
    type(exact_sum_t), intent(inout) :: accs(:)
    integer, intent(in) :: which(:)
    real(rk), intent(in) :: x(:)
    integer :: i, j
    do i = 1, size(x)
      j = which(i)
      call deposit(accs(j)%limb, accs(j)%nonfinite, x(i))
      accs(j)%adds = accs(j)%adds + 1
      if (accs(j)%adds >= NORMALISE_EVERY) call accs(j)%normalise()
    end do
  end subroutine exact_add_each

  !> Add x to the limbs, exactly: from its bits, |x| = m 2^(k - BIAS) with m
  !> < 2^53 (the hidden bit set for a normal number; a subnormal has the
  !> exponent field 0 and the scale of the field 1). m's three 32-bit pieces
  !> at bit k go into three consecutive limbs.
  pure subroutine deposit(limb, nonfinite, x)
    integer(i8), intent(inout) :: limb(0:EXACT_LIMBS - 1)
    integer(i8), intent(inout) :: nonfinite
    real(rk), intent(in) :: x
    integer(i8), parameter :: FIELD = 2047_i8, MANTISSA = 4503599627370495_i8, &
        HIDDEN = 4503599627370496_i8
    integer(i8) :: bits, e, m, t0, t1, t2, sg
    integer :: k, l, s
    bits = transfer(x, bits)
    e = iand(ishft(bits, -52), FIELD)
    if (e == FIELD) then
      nonfinite = nonfinite + 1
      return
    end if
    m = iand(bits, MANTISSA)
    if (e > 0) m = ior(m, HIDDEN)
    if (m == 0) return
    ! The value of the mantissa's bit 0 is 2^(max(e, 1) - 1075) = 2^(k - BIAS).
    k = int(max(e, 1_i8)) - 1075 + BIAS
    l = ishft(k, -5)
    s = k - 32 * l
    ! Shifts below 64 only (0 <= s < 32); sign +-1 without a branch.
    t0 = iand(shiftl(m, s), MASK32)
    t1 = iand(shiftr(m, 32 - s), MASK32)
    t2 = shiftr(shiftr(m, 32), 32 - s)
    sg = 1_i8 + 2_i8 * shifta(bits, 63)
    limb(l) = limb(l) + sg * t0
    limb(l + 1) = limb(l + 1) + sg * t1
    limb(l + 2) = limb(l + 2) + sg * t2
  end subroutine deposit

  !> Carry propagation: limbs 0 .. EXACT_LIMBS-2 in [0, 2^32), the top one
  !> signed (the sign of the sum). Same integer.
  subroutine exact_normalise(acc)
    class(exact_sum_t), intent(inout) :: acc
    integer :: i
    integer(i8) :: carry
    do i = 0, EXACT_LIMBS - 2
      carry = shifta(acc%limb(i), 32)
      acc%limb(i) = iand(acc%limb(i), MASK32)
      acc%limb(i + 1) = acc%limb(i + 1) + carry
    end do
    acc%adds = 0
  end subroutine exact_normalise

  !> The sum as a double: the top three non-zero limbs of its magnitude
  !> (96 bits) added from the largest; NaN when a term was not finite.
  real(rk) function exact_value(acc) result(v)
    type(exact_sum_t), intent(in) :: acc
    type(exact_sum_t) :: a
    logical :: negative
    integer :: i, h
    if (acc%nonfinite > 0) then
      v = ieee_value(1.0_rk, ieee_quiet_nan)
      return
    end if
    a = acc
    call a%normalise()
    negative = a%limb(EXACT_LIMBS - 1) < 0
    if (negative) then
      a%limb = -a%limb
      call a%normalise()
    end if
    v = 0.0_rk
    h = -1
    do i = EXACT_LIMBS - 1, 0, -1
      if (a%limb(i) /= 0) then
        h = i
        exit
      end if
    end do
    if (h < 0) return
    do i = h, max(h - 2, 0), -1
      v = v + scale(real(a%limb(i), rk), 32 * i - BIAS)
    end do
    if (negative) v = -v
  end function exact_value

  !> Normalised limbs and counts of sums into flat (EXACT_PACKED each), for
  !> an integer reduction.
  subroutine exact_pack(sums, flat)
    type(exact_sum_t), intent(inout) :: sums(:)
    integer(i8), intent(out) :: flat(:)
    integer :: j, o
    do j = 1, size(sums)
      call sums(j)%normalise()
      o = (j - 1) * EXACT_PACKED
      flat(o + 1:o + EXACT_LIMBS) = sums(j)%limb
      flat(o + EXACT_PACKED) = sums(j)%nonfinite
    end do
  end subroutine exact_pack

  !> The inverse of exact_pack (the limbs normalised again).
  subroutine exact_unpack(flat, sums)
    integer(i8), intent(in) :: flat(:)
    type(exact_sum_t), intent(inout) :: sums(:)
    integer :: j, o
    do j = 1, size(sums)
      o = (j - 1) * EXACT_PACKED
      sums(j)%limb = flat(o + 1:o + EXACT_LIMBS)
      sums(j)%nonfinite = flat(o + EXACT_PACKED)
      call sums(j)%normalise()
    end do
  end subroutine exact_unpack

end module core_exact_sum
