!> Checks across deck groups that need every group read first, made with the
!> other deck checks so that they are reported in the same run:
!> * the &block named by a &mesh part (block key) exists;
!> * the speeds the deck gives (&region velocity and radial_u0, &boundary
!>   velocity) are below the unit-mistake limit (core_unit_checks) unless
!>   &control allow_high_speed. The speeds of the nodes themselves (a radial
!>   field exceeds radial_u0 inside radial_r0) are checked once the mesh is
!>   built (app_checks).
module io_deck_checks
  use core_kinds, only: rk
  use core_status, only: status_t
  use core_text, only: to_text
  use core_names, only: name_hint
  use core_keys, only: UNSET
  use core_unit_checks, only: speed_limit, speed_limit_text, speed_mistake, brief_text
  use hydro_boundary, only: BC_VELOCITY
  use io_config, only: config_t
  implicit none
  private
  public :: deck_cross_checks

contains

  subroutine deck_cross_checks(config, status)
    type(config_t), intent(in) :: config
    type(status_t), intent(inout) :: status
    integer :: k
    character(len=:), allocatable :: where
    real(rk) :: limit
    if (allocated(config%parts) .and. allocated(config%blocks)) then
      do k = 1, size(config%parts)
        if (len_trim(config%parts(k)%block) == 0) cycle
        if (any(config%blocks%name == config%parts(k)%block)) cycle
        where = '&mesh'
        if (size(config%parts) > 1) where = '&mesh('//to_text(k)//')'
        call status%add(where//': block: '''//trim(config%parts(k)%block)// &
            ''' is not the name of a &block'//name_hint(config%parts(k)%block, &
            config%blocks%name))
      end do
    end if
    limit = speed_limit(config%units)
    if (limit <= 0.0_rk .or. config%allow_high_speed) return
    if (allocated(config%regions)) then
      do k = 1, size(config%regions)
        where = '&region('//to_text(k)//')'
        call check_speed(where//': velocity', norm2(config%regions(k)%velocity))
        call check_speed(where//': radial_u0', abs(config%regions(k)%radial_u0))
      end do
    end if
    if (allocated(config%boundaries)) then
      do k = 1, size(config%boundaries)
        if (config%boundaries(k)%kind /= BC_VELOCITY) cycle
        if (any(config%boundaries(k)%velocity == UNSET)) cycle
        call check_speed('&boundary('//to_text(k)//'): velocity', &
            norm2(config%boundaries(k)%velocity))
      end do
    end if

  contains

    subroutine check_speed(key, speed)
      character(len=*), intent(in) :: key
      real(rk), intent(in) :: speed
      if (.not. (speed > limit)) return
      call status%add(key//': speed '//brief_text(speed)//' is above '// &
          speed_limit_text(config%units)//'; '//speed_mistake(config%units)// &
          ' (if it is meant: &control allow_high_speed = .true.)')
    end subroutine check_speed

  end subroutine deck_cross_checks

end module io_deck_checks
