!> Sorting, the project's one module for it. Every sort is stable (equal keys
!> keep their order), so a permutation depends only on the keys, never on the
!> algorithm: runs of up to SMALL items are sorted by insertion, longer ones
!> by a bottom-up merge sort.
!>
!> * sort_order(key, order): the permutation that sorts key (real or 64-bit
!>   integer) ascending, or the columns of a 64-bit key(:, :)
!>   lexicographically;
!> * sort_values(a): a (real, integer or 64-bit integer) sorted in place;
!> * sort_unique(a): sorted with repeats dropped (64-bit integers);
!> * sorted_find(keys, key): the index of key in ascending keys, 0 if absent.
module core_sort
  use core_kinds, only: rk, i8
  implicit none
  private
  public :: sort_order, sort_values, sort_unique, sorted_find

  !> Below this many items insertion beats merging.
  integer, parameter :: SMALL = 16

  interface sort_order
    module procedure order_real, order_i8, order_columns
  end interface sort_order

  interface sort_values
    module procedure values_real, values_int, values_i8
  end interface sort_values

  !> Index of a key in an ascending array (binary search), 0 if absent.
  interface sorted_find
    module procedure find_i8, find_int
  end interface sorted_find

contains

  !> Stable permutation: key(order) is non-decreasing.
  pure subroutine order_real(key, order)
    real(rk), intent(in) :: key(:)
    integer, allocatable, intent(out) :: order(:)
    integer, allocatable :: work(:)
    integer :: n, width, lo, mid, hi, i, j, k, t

    n = size(key)
    allocate(order(n), work(n))
    order = [(i, i = 1, n)]
    if (n <= SMALL) then
      do i = 2, n
        t = order(i)
        j = i - 1
        do while (j >= 1)
          if (key(order(j)) <= key(t)) exit
          order(j + 1) = order(j)
          j = j - 1
        end do
        order(j + 1) = t
      end do
      return
    end if
    width = 1
    do while (width < n)
      lo = 1
      do while (lo <= n)
        mid = min(lo + width - 1, n)
        hi = min(lo + 2 * width - 1, n)
        i = lo
        j = mid + 1
        do k = lo, hi
          if (i <= mid .and. j <= hi) then
            if (.not. (key(order(i)) <= key(order(j)))) then
              work(k) = order(j)
              j = j + 1
            else
              work(k) = order(i)
              i = i + 1
            end if
          else if (i <= mid) then
            work(k) = order(i)
            i = i + 1
          else
            work(k) = order(j)
            j = j + 1
          end if
        end do
        lo = hi + 1
      end do
      order = work
      width = 2 * width
    end do
  end subroutine order_real

  !> Stable permutation: key(order) is non-decreasing.
  pure subroutine order_i8(key, order)
    integer(i8), intent(in) :: key(:)
    integer, allocatable, intent(out) :: order(:)
    call order_columns(reshape(key, [1, size(key)]), order)
  end subroutine order_i8

  !> Stable permutation: the columns key(:, order) are in lexicographic order.
  pure subroutine order_columns(key, order)
    integer(i8), intent(in) :: key(:, :)
    integer, allocatable, intent(out) :: order(:)
    integer, allocatable :: work(:)
    integer :: n, width, lo, mid, hi, i, j, k, t

    n = size(key, 2)
    allocate(order(n), work(n))
    order = [(i, i = 1, n)]
    if (n <= SMALL) then
      do i = 2, n
        t = order(i)
        j = i - 1
        do while (j >= 1)
          if (.not. less(t, order(j))) exit
          order(j + 1) = order(j)
          j = j - 1
        end do
        order(j + 1) = t
      end do
      return
    end if
    width = 1
    do while (width < n)
      lo = 1
      do while (lo <= n)
        mid = min(lo + width - 1, n)
        hi = min(lo + 2 * width - 1, n)
        i = lo
        j = mid + 1
        do k = lo, hi
          if (i <= mid .and. j <= hi) then
            if (less(order(j), order(i))) then
              work(k) = order(j)
              j = j + 1
            else
              work(k) = order(i)
              i = i + 1
            end if
          else if (i <= mid) then
            work(k) = order(i)
            i = i + 1
          else
            work(k) = order(j)
            j = j + 1
          end if
        end do
        lo = hi + 1
      end do
      order = work
      width = 2 * width
    end do

  contains

    !> Column a before column b.
    pure logical function less(a, b)
      integer, intent(in) :: a, b
      integer :: r
      do r = 1, size(key, 1)
        if (key(r, a) /= key(r, b)) then
          less = key(r, a) < key(r, b)
          return
        end if
      end do
      less = .false.
    end function less

  end subroutine order_columns

  pure subroutine values_real(a)
    real(rk), intent(inout) :: a(:)
    integer, allocatable :: order(:)
    call order_real(a, order)
    a = a(order)
  end subroutine values_real

  pure subroutine values_i8(a)
    integer(i8), intent(inout) :: a(:)
    integer, allocatable :: order(:)
    integer(i8) :: t
    integer :: i, j
    if (size(a) <= SMALL) then
      do i = 2, size(a)
        t = a(i)
        j = i - 1
        do while (j >= 1)
          if (a(j) <= t) exit
          a(j + 1) = a(j)
          j = j - 1
        end do
        a(j + 1) = t
      end do
      return
    end if
    call order_i8(a, order)
    a = a(order)
  end subroutine values_i8

  pure subroutine values_int(a)
    integer, intent(inout) :: a(:)
    integer, allocatable :: order(:)
    integer :: i, j, t
    if (size(a) <= SMALL) then
      do i = 2, size(a)
        t = a(i)
        j = i - 1
        do while (j >= 1)
          if (a(j) <= t) exit
          a(j + 1) = a(j)
          j = j - 1
        end do
        a(j + 1) = t
      end do
      return
    end if
    call order_i8(int(a, i8), order)
    a = a(order)
  end subroutine values_int

  !> Sort ascending and drop repeats.
  pure subroutine sort_unique(a)
    integer(i8), allocatable, intent(inout) :: a(:)
    integer :: i, j
    call values_i8(a)
    j = 0
    do i = 1, size(a)
      if (j > 0) then
        if (a(i) == a(j)) cycle
      end if
      j = j + 1
      a(j) = a(i)
    end do
    a = a(:j)
  end subroutine sort_unique

  !> sorted_find on 64-bit keys.
  pure integer function find_i8(keys, key) result(i)
    integer(i8), intent(in) :: keys(:)
    integer(i8), intent(in) :: key
    integer :: low, high
    low = 1
    high = size(keys)
    do while (low <= high)
      i = (low + high) / 2
      if (keys(i) == key) return
      if (keys(i) < key) then
        low = i + 1
      else
        high = i - 1
      end if
    end do
    i = 0
  end function find_i8

  !> sorted_find on default integer keys.
  pure integer function find_int(keys, key) result(i)
    integer, intent(in) :: keys(:)
    integer, intent(in) :: key
    integer :: low, high
    low = 1
    high = size(keys)
    do while (low <= high)
      i = (low + high) / 2
      if (keys(i) == key) return
      if (keys(i) < key) then
        low = i + 1
      else
        high = i - 1
      end if
    end do
    i = 0
  end function find_int

end module core_sort
