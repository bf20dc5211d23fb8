!> core_sort, core_text and the timer registry of core_timer: sorted order
!> and stability (equal keys keep their order) against a brute-force
!> reference on both sides of the insertion/merge threshold, lexicographic
!> columns, repeats dropped; exact number texts; sections added once, nested,
!> timed and looked up by name.
program test_core
  use core_kinds, only: rk, i8
  use core_sort, only: sort_order, sort_values, sort_unique
  use core_text, only: to_text, fixed_text
  use core_timer, only: timers_t
  use check, only: check_true, check_summary
  implicit none
  integer, parameter :: SIZES(6) = [0, 1, 5, 16, 17, 300]
  real(rk), allocatable :: rkey(:), rv(:)
  integer(i8), allocatable :: ikey(:), cols(:, :), u(:)
  integer, allocatable :: order(:), iv(:)
  real(rk) :: r
  integer :: t, n, i
  character(len=64) :: name
  type(timers_t) :: timers

  call random_seed(put=[(12345 + i, i = 1, 64)])
  do t = 1, size(SIZES)
    n = SIZES(t)
    write(name, '(a,i0)') 'n = ', n
    ! Few distinct values: many ties.
    allocate(rkey(n), ikey(n), cols(2, n))
    do i = 1, n
      call random_number(r)
      rkey(i) = real(int(6.0_rk * r), rk) * 0.5_rk - 1.0_rk
      call random_number(r)
      ikey(i) = int(7.0_rk * r, i8) - 3_i8
      call random_number(r)
      cols(:, i) = [ikey(i), int(3.0_rk * r, i8)]
    end do
    call sort_order(rkey, order)
    call check_true('real order is the stable reference, '//trim(name), &
        all(order == reference(rkey)))
    call sort_order(ikey, order)
    call check_true('i8 order is the stable reference, '//trim(name), &
        all(order == reference(real(ikey, rk))))
    call sort_order(cols, order)
    call check_true('column order is the stable reference, '//trim(name), &
        all(order == reference(real(cols(1, :), rk) * 10.0_rk + real(cols(2, :), rk))))
    rv = rkey
    call sort_values(rv)
    call check_true('real values sorted, '//trim(name), all(rv == rkey(reference(rkey))))
    iv = int(ikey)
    call sort_values(iv)
    call check_true('integer values sorted, '//trim(name), &
        all(iv == int(ikey(reference(real(ikey, rk))))))
    u = ikey
    call sort_unique(u)
    call check_true('unique: strictly ascending, '//trim(name), all(u(2:) > u(:size(u) - 1)))
    call check_true('unique: every key kept, '//trim(name), &
        all([(any(u == ikey(i)), i = 1, n)]) .and. all([(any(ikey == u(i)), i = 1, size(u))]))
    deallocate(rkey, ikey, cols)
  end do

  call check_true('to_text integer', to_text(-42) == '-42')
  call check_true('to_text i8', to_text(9000000000_i8) == '9000000000')
  call check_true('to_text real', to_text(0.5_rk) == '0.50000000000000000')
  call check_true('fixed_text', fixed_text(3600.0_rk, 2) == '3600.00' .and. &
      fixed_text(0.126_rk, 2) == '0.13' .and. fixed_text(-1.5_rk, 1) == '-1.5')

  call timers%add('halo', within='step')
  call timers%add('step')
  call timers%add('dumps')
  call check_true('timers: parent added first, none twice', timers%count == 3 .and. &
      timers%id('step') == 1 .and. timers%id('halo') == 2 .and. timers%id('dumps') == 3)
  call check_true('timers: nesting', timers%parent(2) == 1 .and. timers%parent(1) == 0)
  call check_true('timers: unknown name', timers%id('nothing') == 0 .and. &
      timers%total('nothing') == 0.0_rk)
  call timers%start('dumps')
  do i = 1, 100000
    r = sqrt(real(i, rk))
  end do
  call timers%stop('dumps')
  call timers%start('dumps')
  call timers%stop('dumps')
  call check_true('timers: totals add the intervals', timers%total('dumps') >= &
      timers%last('dumps') .and. timers%last('dumps') >= 0.0_rk .and. &
      timers%total('step') == 0.0_rk)
  call timers%stop('step')
  call check_true('timers: stop without start adds nothing', timers%total('step') == 0.0_rk)
  call timers%start('new')
  call check_true('timers: start adds a section', timers%id('new') == 4)

  call check_summary()

contains

  !> Stable sorting permutation by brute force: rank = number of smaller keys
  !> plus equal keys before.
  function reference(key) result(perm)
    real(rk), intent(in) :: key(:)
    integer, allocatable :: perm(:)
    integer :: a, rank
    allocate(perm(size(key)))
    do a = 1, size(key)
      rank = count(key < key(a)) + count(key(:a - 1) == key(a)) + 1
      perm(rank) = a
    end do
  end function reference

end program test_core
